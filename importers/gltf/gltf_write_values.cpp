// The glTF writer's JSON values (gltf_writer_internal.h): floats written as the
// double of their shortest decimal text, vectors of them, and rayform's own
// extras under the key "rayform".
#include "rayform/importers/gltf/gltf_writer_internal.h"
#include "rayform/importers/text_format.h"

#include <cstdlib>

namespace rayform::gltf_detail {

double nice(float f) {
  double d = std::strtod(format_float(f).c_str(), nullptr);
  return float(d) == f ? d : double(f);
}

Value num(float f) { return Value(nice(f)); }
Value vec_value(vec3 v) { return Value(Value::Array{num(v.x), num(v.y), num(v.z)}); }

std::vector<double> nice_vector(std::initializer_list<float> fs) {
  std::vector<double> out;
  for (float f : fs) out.push_back(nice(f));
  return out;
}

Value rayform_extras(Value::Object obj) {
  Value::Object root;
  root["rayform"] = Value(std::move(obj));
  return Value(std::move(root));
}

}  // namespace rayform::gltf_detail
