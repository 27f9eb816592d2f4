// Wavefront OBJ with its MTL: the input is "OBJ text [\n#MTL\n MTL text]"; every mtllib in the
// OBJ reads the MTL part. Then the same validation loadMesh applies (finishMesh).
#include <string>

#include "fuzz_common.hpp"
#include "loaders.hpp"

PRT_FUZZ_TARGET({
  const std::string_view all = prt::fuzz::text(data, size);
  const std::size_t cut = all.find("\n#MTL\n");
  const std::string_view obj = all.substr(0, cut);
  const std::string mtl(cut == std::string_view::npos ? std::string_view() : all.substr(cut + 6));
  prt::LoadReport report;
  prt::Mesh m = prt::detail::readObjText("fuzz.obj", obj, "", &mtl, report);
  prt::detail::finishMesh(m, "fuzz.obj", report);
})
