#pragma once
// A builtin scene (builtin:NAME?...) and its Embree occluder: what the bake tests trace against.

#include <memory>
#include <string>

#include "prt/geometry/builtin.hpp"
#include "prt/raytrace/occluder.hpp"

namespace prt::testdata {

struct BuiltinScene {
  Mesh mesh;
  std::unique_ptr<Occluder> occluder;
  explicit BuiltinScene(const std::string& name)
      : mesh(builtinScene(name)), occluder(makeEmbreeOccluder(mesh)) {}
};

}  // namespace prt::testdata
