// The visual meshes the 3D view reads: urdf-loader's own .stl and .dae loaders, and .obj, which it does not read.
// urdf-loader puts each mesh in the frame the URDF means, as rviz and Gazebo do: it resets the rotation three.js's
// ColladaLoader gives a Z_UP file (to make it y-up) and keeps its <unit meter> scale.
import * as THREE from 'three';
import { ColladaLoader } from 'three/examples/jsm/loaders/ColladaLoader.js';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';

// A mesh's URL as the server serves it: a file:// URI (xacro's force_abs_paths, UR's descriptions) resolved against
// the URDF's URL becomes /file/<absolute path>, which the server answers inside the package path and the URDF's folder.
export function meshUrl(path) {
  const at = path.indexOf('file://');
  return at < 0 ? path : `/file${path.slice(at + 'file://'.length)}`;
}

// urdf-loader's loadMeshCb: (path, manager, material, done(object, error)).
export function loadMesh(path, manager, material, done) {
  path = meshUrl(path);
  const failed = (err) => done(null, err);
  if (/\.stl$/i.test(path)) {
    new STLLoader(manager).load(path, (geometry) => done(new THREE.Mesh(geometry, material || new THREE.MeshPhongMaterial())), null, failed);
  } else if (/\.dae$/i.test(path)) {
    new ColladaLoader(manager).load(path, (dae) => done(dae.scene), null, failed);
  } else if (/\.obj$/i.test(path)) {
    new OBJLoader(manager).load(path, (group) => {
      if (material) group.traverse((o) => { if (o.isMesh) o.material = material; });
      done(group);
    }, null, failed);
  } else {
    failed(new Error(`no loader for ${path} (the dashboard shows .stl, .dae and .obj meshes)`));
  }
}
