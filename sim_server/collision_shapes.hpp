// Bullet collision shapes for URDF collision geometry: box, cylinder (along z),
// sphere, and STL (any assimp format) meshes as convex hulls.
#pragma once

#include <btBulletCollisionCommon.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control::sim {

// Owns every shape built for one world.
using ShapeStore = std::vector<std::unique_ptr<btCollisionShape>>;

// The shape of one link, its geometries placed by com_from_link * origin (the
// link's collision geometry seen from its Bullet COM frame). nullptr when the
// link has no collision geometry. Throws ModelError for an unreadable mesh.
btCollisionShape* make_link_shape(const Link& link, const Eigen::Isometry3d& com_from_link, ShapeStore& store,
                                  const std::string& urdf_path);

btTransform to_bt(const Eigen::Isometry3d& t);
Eigen::Isometry3d from_bt(const btTransform& t);

}  // namespace lcm_control::sim
