#pragma once
// prt web: the page's environments, and its --json report (docs/formats-report.md): the folder,
// the bake, what the page draws and what it opens on.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "prt/core/json.hpp"
#include "prt/haar/turned_cube.hpp"
#include "prt/image/image.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/sh/sh.hpp"
#include "web.hpp"

namespace prt::cli {

/// One environment of the page: its SH light and the background the page draws.
struct WebEnvironment {
  std::string spec;  ///< as given (--env)
  std::string name;
  sh::RgbSh light;
  image::Image background;  // lat-long, linear RGB
  /// A Haar bake's: the environment's cube the page turns its light from (haar/turned_cube.hpp).
  std::optional<haar::EnvironmentCube> haar;
};

/// What writeWebViewer decided and wrote, for the report.
struct WebPageFacts {
  std::string shown;          ///< the folder as messages name it
  std::size_t bakeBytes = 0;  ///< the bake as the page reads it
  bool embedded = false;      ///< in prt-data.js, or beside it as kBakeFileName
  std::size_t texelPointsBytes = 0;
  int bands = 0;
  float exposureStops = 0;
  Json glossy;  ///< the page data's "glossy" member: the material per glossy transfer
};

/// The report's members: folder, bake, mesh, transfers, bands, environments, view.
Json webReport(const WebOptions& a, const BakeFile& bake, const std::vector<WebEnvironment>& envs,
               const WebPageFacts& facts);

}  // namespace prt::cli
