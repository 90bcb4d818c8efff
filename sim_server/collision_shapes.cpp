#include "sim_server/collision_shapes.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

namespace lcm_control::sim {

btTransform to_bt(const Eigen::Isometry3d& t) {
  const Eigen::Matrix3d r = t.rotation();
  const Eigen::Vector3d p = t.translation();
  return btTransform(btMatrix3x3(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)),
                     btVector3(p.x(), p.y(), p.z()));
}

Eigen::Isometry3d from_bt(const btTransform& t) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  const btMatrix3x3& r = t.getBasis();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.linear()(i, j) = r[i][j];
  out.translation() << t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z();
  return out;
}

namespace {

void collect_vertices(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, btConvexHullShape& hull,
                      const Eigen::Vector3d& scale) {
  const aiMatrix4x4 t = parent * node->mTransformation;
  for (unsigned m = 0; m < node->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = t * mesh->mVertices[v];
      hull.addPoint(btVector3(p.x * scale.x(), p.y * scale.y(), p.z * scale.z()), false);
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) collect_vertices(scene, node->mChildren[c], t, hull, scale);
}

std::unique_ptr<btCollisionShape> make_mesh(const Geometry& g, const std::string& where) {
  Assimp::Importer importer;
  // A Collada file's <up_axis> would become a rotation of the root node (Z_UP to Assimp's Y_UP); rviz, Gazebo and
  // geometric_shapes take the vertices in the URDF's frame as exported, so it is left out. The root node keeps the
  // file's <unit meter> scale.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(g.mesh_path, aiProcess_JoinIdenticalVertices);
  if (!scene || !scene->mRootNode)
    throw ModelError(fmt::format("{}: cannot read collision mesh '{}' ({}): {}", where, g.mesh_uri, g.mesh_path,
                                 importer.GetErrorString()));
  auto hull = std::make_unique<btConvexHullShape>();
  collect_vertices(scene, scene->mRootNode, aiMatrix4x4(), *hull, g.scale);
  if (hull->getNumPoints() < 4)
    throw ModelError(fmt::format("{}: collision mesh '{}' has {} vertices; a convex hull needs at least 4", where,
                                 g.mesh_uri, hull->getNumPoints()));
  hull->setMargin(0.001);  // Bullet's 4 cm default would inflate the hull
  hull->optimizeConvexHull();
  hull->recalcLocalAabb();
  return hull;
}

std::unique_ptr<btCollisionShape> make_shape(const Geometry& g, const std::string& where) {
  switch (g.type) {
    case Geometry::Type::Box:
      return std::make_unique<btBoxShape>(btVector3(g.size.x() / 2, g.size.y() / 2, g.size.z() / 2));
    case Geometry::Type::Cylinder:
      return std::make_unique<btCylinderShapeZ>(btVector3(g.radius, g.radius, g.length / 2));
    case Geometry::Type::Sphere:
      return std::make_unique<btSphereShape>(g.radius);
    case Geometry::Type::Mesh:
      return make_mesh(g, where);
  }
  return nullptr;
}

}  // namespace

btCollisionShape* make_link_shape(const Link& link, const Eigen::Isometry3d& com_from_link, ShapeStore& store,
                                  const std::string& urdf_path) {
  if (link.collisions.empty()) return nullptr;
  const std::string where = fmt::format("{}: link '{}'", urdf_path, link.name);
  auto compound = std::make_unique<btCompoundShape>(false, int(link.collisions.size()));
  compound->setMargin(0);
  for (const Geometry& g : link.collisions) {
    store.push_back(make_shape(g, where));
    compound->addChildShape(to_bt(com_from_link * g.origin), store.back().get());
  }
  store.push_back(std::move(compound));
  return store.back().get();
}

}  // namespace lcm_control::sim
