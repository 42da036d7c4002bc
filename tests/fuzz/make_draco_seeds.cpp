// Writes glTF seeds that use KHR_draco_mesh_compression into OUT/gltf/:
//   rayform_fuzz_draco_seeds OUT
// A program of its own because Draco's encoder pulls in the copy of tinygltf
// that libdraco carries, which must not meet the glTF reader (see
// tests/CMakeLists.txt on the compression tests).
#include "rayform/scene/procedural_mesh.h"
#include "seed_files.h"

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <iostream>

using namespace rayform;
using namespace rayform::fuzz;

namespace {

// Draco: positions and normals in one compressed primitive.
void draco_seeds(const GltfMesh& g) {
  draco::TriangleSoupMeshBuilder b;
  const size_t faces = g.indices.size() / 3;
  b.Start(int(faces));
  const int pos = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nrm = b.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  for (size_t f = 0; f < faces; ++f) {
    const uint32_t* i = &g.indices[3 * f];
    b.SetAttributeValuesForFace(pos, draco::FaceIndex(uint32_t(f)), &g.positions[3 * i[0]], &g.positions[3 * i[1]],
                                &g.positions[3 * i[2]]);
    b.SetAttributeValuesForFace(nrm, draco::FaceIndex(uint32_t(f)), &g.normals[3 * i[0]], &g.normals[3 * i[1]],
                                &g.normals[3 * i[2]]);
  }
  std::unique_ptr<draco::Mesh> mesh = b.Finalize();
  mesh->attribute(pos)->set_unique_id(0);
  mesh->attribute(nrm)->set_unique_id(1);
  for (int method : {draco::MESH_SEQUENTIAL_ENCODING, draco::MESH_EDGEBREAKER_ENCODING}) {
    draco::Encoder enc;
    enc.SetEncodingMethod(method);
    if (method == draco::MESH_EDGEBREAKER_ENCODING)
      enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 11);
    draco::EncoderBuffer buf;
    if (!enc.EncodeMeshToBuffer(*mesh, &buf).ok()) continue;
    const std::string bin(buf.data(), buf.size());
    std::ostringstream j;
    j << "{" << gltf_head
      << R"("extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"],)"
      << R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"indices":2,)"
      << R"("extensions":{"KHR_draco_mesh_compression":{"bufferView":0,"attributes":{"POSITION":0,"NORMAL":1}}}}]}],)"
      << R"("accessors":[{"componentType":5126,"count":)" << mesh->num_points() << R"(,"type":"VEC3",)" << minmax(g)
      << R"(},{"componentType":5126,"count":)" << mesh->num_points() << R"(,"type":"VEC3"},)"
      << R"({"componentType":5125,"count":)" << faces * 3 << R"(,"type":"SCALAR"}],)"
      << R"("bufferViews":[{"buffer":0,"byteLength":)" << bin.size() << "}],";
    const std::string tag = method == draco::MESH_SEQUENTIAL_ENCODING ? "sequential" : "edgebreaker";
    seed("gltf", "draco_" + tag + ".gltf",
         j.str() + R"("buffers":[{"byteLength":)" + std::to_string(bin.size()) + R"(,"uri":")" + data_uri(bin) +
             "\"}]}");
    seed("gltf", "draco_" + tag + ".glb",
         glb(j.str() + R"("buffers":[{"byteLength":)" + std::to_string(bin.size()) + "}]}", bin));
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: rayform_fuzz_draco_seeds OUT\n";
    return 2;
  }
  out_root = argv[1];
  draco_seeds(gltf_mesh(make_icosphere(1)));
  std::cout << written << " Draco seed files in " << out_root.string() << "\n";
}
