#include "shape/shape.h"

namespace invfree {

const char* shape_kind_name(ShapeKind k) {
  return enum_name(kShapeKindNames, k);
}

std::optional<ShapeKind> shape_kind_from_name(std::string_view name) {
  return enum_from_name(kShapeKindNames, name);
}

}  // namespace invfree
