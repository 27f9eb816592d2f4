// Files: bake files (read_bake, read_bake_file, write_bake), light files, the GAMES202
// course's light.txt and transport.txt, and images — the library's readers and writers, so a
// file written here is one `prt` reads and the other way round.

#include <cmath>
#include <cstring>

#include "common.hpp"
#include "objects.hpp"
#include "prt/core/version.hpp"
#include "prt/image/exposure.hpp"
#include "prt/image/image_io.hpp"
#include "prt/io/bake_file.hpp"
#include "prt/core/file.hpp"
#include "prt/io/engine_light.hpp"
#include "prt/io/games202_transport.hpp"
#include "prt/io/light_file.hpp"
#include "prt/relight/view_transfer.hpp"

namespace prtpy {

namespace {

/// The file's choice of transfer: prt::pickTransfer with optional mode and layout names.
std::size_t pick(const prt::BakeFile& file, const std::optional<std::string>& mode,
                 const std::optional<std::string>& layout, const std::string& path) {
  std::optional<prt::TransferMode> m;
  std::optional<prt::TransferLayout> l;
  asValueError([&] {
    if (mode) m = prt::parseTransferMode(*mode);
    if (layout) l = prt::parseTransferLayout(*layout);
    return 0;
  });
  const prt::BakedTransfer& t = prt::pickTransfer(file, m, l, path);
  return static_cast<std::size_t>(&t - file.transfers.data());
}

TransferPtr pyTransfer(const prt::BakedTransfer& b) {
  auto t = std::make_shared<PyTransfer>();
  t->transfer = b.transfer;
  t->recipe = b.recipe;
  t->stats = b.stats;
  if (b.transfer.compressed()) t->compression = b.compression;
  return t;
}

/// prtkit.BakeFile: a bake file as read.
struct PyBakeFile {
  prt::BakeFile file;  ///< its transfers (the mesh moved to `mesh`)
  MeshPtr mesh;
  std::vector<TransferPtr> transfers;
  std::string path;
};

/// `shOnly`: read_bake's dense numpy rows hold SH transfer only (a Haar bake's rows are sparse
/// wavelet terms: read_bake_file reads them as prtkit.Transfer).
prt::BakeFile readFile(const std::string& path, bool shOnly) {
  py::gil_scoped_release nogil;
  prt::BakeFile f = prt::readBake(path);
  if (shOnly)
    f.requireSh(path, "read_bake returns SH rows as numpy: read_bake_file reads Haar transfer");
  prt::foldBaseColour(f.mesh);  // as load_mesh: the module shades per vertex (and per texel)
  return f;
}

py::dict lightDict(const prt::io::LightFile& f) {
  py::dict d;
  d["coefficients"] = lightArray(f.coefficients);
  d["source"] = f.source;
  d["layout"] = f.layout;
  d["window"] = f.window;
  d["rotation"] = py::make_tuple(f.rotationDeg[0], f.rotationDeg[1], f.rotationDeg[2]);
  d["prtkit_version"] = f.prtkitVersion;
  return d;
}

prt::Games202Layout games202Layout(const std::string& s) {
  if (s == "faces") return prt::Games202Layout::Faces;
  if (s == "vertices") return prt::Games202Layout::Vertices;
  throw py::value_error("layout must be faces (the course's file) or vertices, got '" + s + "'");
}

}  // namespace

void bindFiles(py::module_& m) {
  py::class_<PyBakeFile, std::shared_ptr<PyBakeFile>>(
      m, "BakeFile",
      R"(A bake file (.glb) as read: the mesh and its transfers, each with how it was baked.)")
      .def_property_readonly("mesh", [](const PyBakeFile& f) { return f.mesh; })
      .def_property_readonly("transfers", [](const PyBakeFile& f) { return f.transfers; })
      .def_property_readonly("format_version",
                             [](const PyBakeFile& f) { return f.file.formatVersion; })
      .def_property_readonly("generator", [](const PyBakeFile& f) { return f.file.generator; })
      .def_property_readonly(
          "rows",
          [](const PyBakeFile& f) {
            const prt::RowRange r = f.file.rows();
            return py::make_tuple(r.first, r.end());
          },
          "(first, end): the vertices the transfers cover.")
      .def_property_readonly(
          "complete",
          [](const PyBakeFile& f) {
            const prt::RowRange r = f.file.rows();
            return r.first == 0 && r.count == f.mesh->mesh().vertexCount();
          },
          "True when the transfers cover every vertex (not a split bake's part).")
      .def(
          "pick",
          [](const PyBakeFile& f, std::optional<std::string> mode,
             std::optional<std::string> transfer) {
            return f.transfers[pick(f.file, mode, transfer, f.path)];
          },
          py::arg("mode") = py::none(), py::arg("transfer") = py::none(),
          "The transfer of `mode` (default: the richest) and layout `transfer` ('vector' or "
          "'matrix'; default: a matrix before a vector): the choice every prt verb makes.")
      .def("__repr__", [](const PyBakeFile& f) {
        std::string s = "<prtkit.BakeFile " + f.path + ": " + f.mesh->mesh().source + ", ";
        for (std::size_t i = 0; i < f.file.transfers.size(); ++i)
          s += (i ? ", " : "") + f.file.transfers[i].describe();
        return s + ">";
      });

  m.def(
      "read_bake",
      [](py::handle pathObj, std::optional<std::string> mode, std::optional<std::string> transfer) {
        const std::string path = pathString(pathObj);
        prt::Transfer t;
        {
          prt::BakeFile file = readFile(path, true);
          const std::size_t i = pick(file, mode, transfer, path);
          t = std::move(file.transfers[i].transfer);
        }
        if (t.compressed()) {
          py::gil_scoped_release nogil;
          t = t.toDense();
        }
        // The file is gone: vector rows are held by the transfer alone (writable, no copy);
        // matrix rows view the file's bytes (read-only, no copy).
        return transferArray(std::move(t), true);
      },
      py::arg("path"), py::arg("mode") = py::none(), py::arg("transfer") = py::none(),
      R"(The dense transfer a bake file holds, as bake returns it (same shapes; the same values,
bit for bit, as the bake that wrote the file). mode: which transfer ('shadowed', ...;
default the richest); transfer: 'vector' or 'matrix' (default: a matrix first). A compressed
transfer is reconstructed. No copy is made: vector rows are owned by the array (writable),
matrix rows view the file's bytes (read-only).)");

  m.def(
      "read_bake_file",
      [](py::handle pathObj) {
        auto f = std::make_shared<PyBakeFile>();
        f->path = pathString(pathObj);
        f->file = readFile(f->path, false);
        f->mesh = std::make_shared<PyMesh>(std::move(f->file.mesh));
        f->file.mesh = prt::Mesh{};
        for (const prt::BakedTransfer& b : f->file.transfers) f->transfers.push_back(pyTransfer(b));
        return f;
      },
      py::arg("path"), "Reads a bake file: a prtkit.BakeFile (mesh, transfers with recipes).");

  m.def(
      "write_bake",
      [](py::handle pathObj, py::handle meshObj, py::handle transfers,
         std::optional<std::string> mode) {
        const std::string path = pathString(pathObj);
        const MeshPtr mesh = toMesh(meshObj);
        std::vector<TransferPtr> list;
        if (py::isinstance<PyTransfer>(transfers) || py::isinstance<py::array>(transfers))
          list.push_back(toTransfer(transfers));
        else
          for (py::handle t : transfers) list.push_back(toTransfer(t));
        if (list.empty()) throw py::value_error("write_bake: no transfer given");
        prt::BakeFile file;
        file.mesh = mesh->mesh();
        for (std::size_t i = 0; i < list.size(); ++i) {
          const PyTransfer& t = *list[i];
          prt::BakedTransfer b;
          if (t.recipe) {
            b.recipe = *t.recipe;
          } else if (mode) {
            b.recipe.mode = asValueError([&] { return prt::parseTransferMode(*mode); });
            b.recipe.bounces = 0;
          } else {
            throw py::value_error("transfer " + std::to_string(i) +
                                  " records no recipe: give mode= (or a Transfer(..., mode=...))");
          }
          if (t.stats) b.stats = *t.stats;
          if (t.compression) b.compression = *t.compression;
          b.transfer = t.transfer;
          // As prt bake: a bake's kd replaces the mesh's albedo in the file, so every reader
          // relights with the albedo the bounces were baked with.
          if (b.recipe.material.diffuse)
            file.mesh.albedo.assign(file.mesh.vertexCount(), *b.recipe.material.diffuse);
          file.transfers.push_back(std::move(b));
        }
        py::gil_scoped_release nogil;
        prt::writeBake(path, file);
      },
      py::arg("path"), py::arg("mesh"), py::arg("transfers"), py::arg("mode") = py::none(),
      R"(Writes a bake file (.glb, written atomically) that prt and the viewers read: the mesh and one
transfer or a list (prtkit.Transfer, or a numpy array with mode= naming its mode; at most one
per mode and layout; their rows must be the same range). A transfer's recipe (bake_transfer,
read_bake_file) is stored with it.)");

  m.def(
      "read_light",
      [](py::handle pathObj) {
        const std::string path = pathString(pathObj);
        return lightArray(prt::io::readLight(path).coefficients);
      },
      py::arg("path"),
      "SH lighting (B², 3) from a light file: our JSON, or the course's light.txt (by extension).");
  m.def(
      "read_light_file",
      [](py::handle pathObj) { return lightDict(prt::io::readLight(pathString(pathObj))); },
      py::arg("path"),
      "A light file with its metadata: a dict (coefficients, source, layout, window, rotation, "
      "prtkit_version).");
  m.def(
      "write_light",
      [](py::handle pathObj, py::handle lightObj, std::optional<std::string> format,
         const std::string& source, const std::string& layout, const std::string& window,
         py::handle rotationDeg) {
        const std::string path = pathString(pathObj);
        const prt::sh::RgbSh l = light(lightObj);
        std::string f = format.value_or("");
        if (f.empty()) {
          const auto dot = path.rfind('.');
          f = dot != std::string::npos && path.substr(dot) == ".txt" ? "games202" : "json";
        }
        if (f == "games202") {
          prt::io::writeLightGames202(path, l);
          return;
        }
        if (f != "json") {
          // An engine's convention (io/engine_light.hpp): threejs, gltf-ibl, cmgen, unity.
          prt::io::EngineLight engine;
          try {
            engine = prt::io::parseEngineLight(f);
          } catch (const prt::Error&) {
            throw py::value_error("format must be json, games202, threejs, gltf-ibl, cmgen or "
                                  "unity, got '" + f + "'");
          }
          prt::writeFileAtomically(path, prt::io::formatEngineLight(engine, l, source));
          return;
        }
        prt::io::LightFile lf;
        lf.coefficients = l;
        lf.source = source;
        lf.layout = layout;
        lf.window = window;
        const auto r = doubles(rotationDeg, "rotation", {3});
        lf.rotationDeg = {r.data()[0], r.data()[1], r.data()[2]};
        lf.prtkitVersion = prt::kVersion;
        prt::io::writeLightJson(path, lf);
      },
      py::arg("path"), py::arg("light"), py::kw_only(), py::arg("format") = py::none(),
      py::arg("source") = "", py::arg("layout") = "", py::arg("window") = "none",
      py::arg("rotation") = py::make_tuple(0, 0, 0),
      "Writes SH lighting (B², 3) as `prt light` does: JSON, or the course's light.txt "
      "(format='games202', the default for .txt), or an engine's convention (format='threejs', "
      "'gltf-ibl', 'cmgen', 'unity': docs/formats-light.md). source, layout, window and "
      "rotation (Euler degrees) are recorded in the JSON only (source also in engine files).");

  m.def(
      "read_games202_transport",
      [](py::handle pathObj) {
        prt::Games202Transport t = prt::readGames202Transport(pathString(pathObj));
        py::dict d;
        d["vertex_count"] = t.vertexCount;
        d["bands"] = t.bands;
        d["layout"] = t.layout == prt::Games202Layout::Faces ? "faces" : "vertices";
        d["rows"] = adoptVector(std::move(t.rows), {static_cast<py::ssize_t>(t.rowCount),
                                                    static_cast<py::ssize_t>(t.bands * t.bands)});
        return d;
      },
      py::arg("path"),
      "The course's transport.txt: a dict (vertex_count, bands, layout 'faces' or 'vertices', "
      "rows (R, B²) float32).");
  m.def(
      "write_games202_transport",
      [](py::handle pathObj, py::handle transferObj, py::handle meshObj, const std::string& layout,
         std::optional<std::string> channel) {
        const std::string path = pathString(pathObj);
        const TransferPtr t = toTransfer(transferObj);
        requireShTransfer(*t, "the course's transport files hold SH rows");
        const MeshPtr mesh = toMesh(meshObj);
        const prt::Games202Layout lay = games202Layout(layout);
        std::optional<prt::ChannelSelect> ch;
        if (channel) ch = asValueError([&] { return prt::parseChannelSelect(*channel); });
        // As prt export: the reconstruction of compressed rows, a matrix's diffuse part, one
        // channel of RGB transfer.
        prt::Transfer field = t->transfer.toDense();
        if (field.isMatrix()) field = prt::relight::diffuseTransfer(field, mesh->mesh().normals);
        if (field.channels() == 3) {
          if (!ch)
            throw py::value_error(
                "the transfer is RGB (coloured inter-reflection) and transport.txt holds one value "
                "per coefficient: pick channel='luminance', 'r', 'g' or 'b'");
          field = prt::selectChannel(field, *ch);
        }
        if (field.bands() != 3)
          warn(std::to_string(field.bands()) +
               " bands: the course's shaders expect 3 bands (9 coefficients per line)");
        py::gil_scoped_release nogil;
        prt::writeGames202Transport(path, field, mesh->mesh(), lay);
      },
      py::arg("path"), py::arg("transfer"), py::arg("mesh"), py::arg("layout") = "faces",
      py::arg("channel") = py::none(),
      "Writes the course's transport.txt as `prt export --format games202` does (layout faces: 3 "
      "lines per triangle; vertices: one per vertex). Matrices export their diffuse part, RGB "
      "transfer one channel (channel='luminance' | 'r' | 'g' | 'b').");

  m.def(
      "read_image",
      [](py::handle pathObj, const std::string& decode) {
        prt::image::ReadOptions o;
        if (decode == "srgb")
          o.ldrDecode = prt::image::LdrDecode::Srgb;
        else if (decode == "gamma2.2")
          o.ldrDecode = prt::image::LdrDecode::Gamma22;
        else
          throw py::value_error("decode must be srgb or gamma2.2");
        const std::string path = pathString(pathObj);
        prt::image::ReadStats st;
        prt::image::Image img;
        {
          py::gil_scoped_release nogil;
          img = prt::image::readImage(path, o, &st);
        }
        if (st.nonFinitePixels + st.negativePixels)
          warn(path + ": " + std::to_string(st.nonFinitePixels) + " non-finite and " +
               std::to_string(st.negativePixels) + " negative pixels set to 0");
        const auto h = static_cast<py::ssize_t>(img.height),
                   w = static_cast<py::ssize_t>(img.width);
        return adoptVector(std::move(img.pixels), {h, w, 3});
      },
      py::arg("path"), py::arg("decode") = "srgb",
      "An image (.hdr, .exr, .png, .jpg) as (H, W, 3) linear float32 (8-bit formats decoded "
      "from sRGB, or (v/255)^2.2 with decode='gamma2.2').");
  m.def(
      "write_image",
      [](py::handle pathObj, py::handle image, const std::string& tonemap, py::handle exposure) {
        const std::string path = pathString(pathObj);
        const auto a = floats(image, "image", {kAny, kAny, 3});
        prt::image::Image img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
        std::memcpy(static_cast<void*>(img.pixels.data()), a.data(),
                    img.pixels.size() * sizeof(prt::Rgb));
        prt::image::WriteOptions o;
        o.toneMap = asValueError([&] { return prt::image::parseToneMap(tonemap); });
        if (py::isinstance<py::str>(exposure)) {
          if (exposure.cast<std::string>() != "auto")
            throw py::value_error("exposure must be a number of stops or 'auto'");
          // prt render's rule (image::autoExposure) over the pixels that are not black: of a
          // render(background='none'), exactly the mesh's.
          std::vector<prt::Rgb> shown;
          for (const prt::Rgb& p : img.pixels)
            if (prt::isFinite(p) && (p.x > 0 || p.y > 0 || p.z > 0)) shown.push_back(p);
          o.exposureStops = prt::image::autoExposure(shown, o.toneMap);
        } else {
          o.exposureStops = exposure.cast<float>();
          if (!std::isfinite(o.exposureStops))
            throw py::value_error("exposure must be finite");
        }
        py::gil_scoped_release nogil;
        prt::image::writeImage(path, img, o);
      },
      py::arg("path"), py::arg("image"), py::arg("tonemap") = "aces", py::arg("exposure") = "auto",
      "Writes an (H, W, 3) linear image: .exr / .hdr linear, .png tone-mapped (aces, reinhard, "
      "clamp) and sRGB-encoded, as prt render writes them. exposure: stops, or 'auto' (default): "
      "prt render's auto exposure over the image's non-black pixels (of a render with "
      "background='none', the mesh's; with a background, pass auto_exposure(mesh, radiance, ...)).");
}

}  // namespace prtpy
