#pragma once
// What every part of the prtkit module shares: checked numpy input, zero-copy numpy output,
// argument parsing that raises ValueError, and the runner that keeps a long call interruptible.
//
// Arrays in. Arrays that are copied into library types anyway (mesh vertices, a light, an
// image) may be any real dtype, any strides, a list; arrays the library reads in place (a
// transfer) must be C-contiguous float32, because converting them would be a hidden copy of
// what may be gigabytes. Anything else — a wrong dtype, shape or layout, a NaN or infinity — is
// a ValueError naming the argument and the problem, never a crash.
//
// Arrays out. A result the library allocated (a bake's transfer, a relighting, an image) is
// handed to numpy without a copy: the array's base is a capsule that owns the C++ value.
//
// Long calls (bake, reference, validate, compress, render, projection) run on a helper thread
// while the calling thread waits with the GIL released, waking every 50 ms to run Python's
// signal handlers and the progress callback (runLong).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "prt/core/error.hpp"
#include "prt/core/float_array.hpp"
#include "prt/core/progress.hpp"
#include "prt/core/vec.hpp"
#include "prt/sh/sh.hpp"

namespace prtpy {

namespace py = pybind11;
using Shape = std::vector<py::ssize_t>;
/// In a shape pattern: any extent.
inline constexpr py::ssize_t kAny = -1;

// --- errors --------------------------------------------------------------------------------

/// prt::Error → prtkit.Error (a RuntimeError), prt::Cancelled → prtkit.Cancelled.
void registerExceptions(py::module_& m);

/// Runs f(); a prt::Error it throws (a bad mode name, material spec, ...) becomes a ValueError
/// with the library's message: for arguments, not for files or work.
template <class F>
auto asValueError(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const prt::Cancelled&) {
    throw;
  } catch (const prt::Error& e) {
    throw py::value_error(e.what());
  }
}

/// Issues a Python UserWarning with `message` (the CLI's "warning:" lines).
void warn(const std::string& message);

// --- arrays in -----------------------------------------------------------------------------

/// `obj` as a C-contiguous float32 array of `shape` (kAny: any extent), converted from any
/// real dtype, list or strided array (a copy only when needed). ValueError naming `what` on a
/// non-numeric dtype, a wrong shape, or (unless allowNonFinite) a NaN or infinity.
py::array_t<float, py::array::c_style> floats(py::handle obj, const char* what, const Shape& shape,
                                              bool allowNonFinite = false);
/// The same in double precision.
py::array_t<double, py::array::c_style> doubles(py::handle obj, const char* what,
                                                const Shape& shape, bool allowNonFinite = false);
/// `obj` as it is, without conversion: a float32, C-contiguous numpy array of `ndim` 2..4
/// dimensions (ValueError otherwise, saying how to make one). For data read in place.
py::array inPlaceFloats(py::handle obj, const char* what);
/// Throws a ValueError naming `what` and the first index whose value is not finite.
void requireFinite(const float* data, std::size_t n, const char* what, const Shape& shape);
/// An (N, 3) array of integer indices, each < `limit` (ValueError naming `what` otherwise).
std::vector<std::array<std::uint32_t, 3>> triangles(py::handle obj, const char* what,
                                                    std::size_t limit);
/// A 1-D array of integer indices, each < `limit`.
std::vector<std::uint32_t> indices(py::handle obj, const char* what, std::size_t limit);
/// Three numbers.
prt::Vec3f vec3(py::handle obj, const char* what);
/// An RGB colour: one grey number or three.
prt::Rgb rgb(py::handle obj, const char* what);
/// Per-row albedo: (rows, 3), or one colour for every row.
std::vector<prt::Rgb> albedoOf(py::handle obj, std::size_t rows);
/// True for a path argument: a str or an os.PathLike.
bool isPath(py::handle obj);
/// A path argument as a string (os.fspath).
std::string pathString(py::handle obj);
/// A rotation: a 3×3 matrix (applied to column vectors: a feature at d moves to R d), or three
/// Euler angles in degrees about X, then Y, then Z (R = Rz Ry Rx, as `prt --rotate X,Y,Z`).
/// None: the identity.
prt::Mat3d rotation(py::handle obj, const char* what = "rotation");
/// SH lighting: an array of shape (B², 3) (B² = 1, 4, 9, ...).
prt::sh::RgbSh light(py::handle obj, const char* what = "light");

// --- arrays out ----------------------------------------------------------------------------

/// Something that owns the memory an array views (what the capsule holds).
struct Buffer {
  virtual ~Buffer() = default;
  const void* data = nullptr;  ///< the first element (prtkit._buffer_address reports it)
};
template <class T>
struct Owned : Buffer {
  T value;
  explicit Owned(T v) : value(std::move(v)) {}
};
/// The name of the capsules that own result buffers.
inline constexpr const char* kBufferCapsule = "prtkit.buffer";
/// A capsule owning `buffer` (deleted when the last array viewing it goes).
py::capsule capsule(std::unique_ptr<Buffer> buffer);
/// An array of `dtype` and `shape` (C order) over `data`, kept alive by `base`; read-only
/// unless `writable`.
py::array view(py::dtype dtype, const Shape& shape, const void* data, py::handle base,
               bool writable);
/// A float32 array of `shape` over the vector's storage, without a copy.
template <class T>
py::array adoptVector(std::vector<T> v, const Shape& shape) {
  auto owned = std::make_unique<Owned<std::vector<T>>>(std::move(v));
  owned->data = owned->value.data();
  const void* data = owned->data;
  py::capsule base = capsule(std::move(owned));
  return view(py::dtype::of<float>(), shape, data, base, true);
}
/// SH lighting as a (B², 3) float32 array.
py::array lightArray(const prt::sh::RgbSh& light);

/// Keeps a Python object alive from C++ (a numpy array viewed in place); the last owner
/// releases it under the GIL.
std::shared_ptr<const void> keepAlive(py::object obj);

// --- long calls ----------------------------------------------------------------------------

/// Runs work(progress) on a helper thread; the caller (holding the GIL) waits with the GIL
/// released, waking every 50 ms to
///   * run Python's signal handlers (PyErr_CheckSignals; in the main thread only): an
///     exception from them (KeyboardInterrupt on Ctrl-C) cancels the work at once through the
///     process-wide flag the CLI's SIGINT handler sets (prt::requestCancel, checked by every
///     Progress at each chunk of work), waits for it to stop and is raised. As in the CLI the
///     flag stops every long call in progress (those of other threads raise prtkit.Cancelled);
///     it is cleared when the last of them has returned;
///   * call `progress` — None, a callable taking the fraction done (returning False cancels:
///     prtkit.Cancelled), or True for a tqdm bar labelled `label` when tqdm is installed.
/// Exceptions of the work are rethrown here (prtkit.Error, prtkit.Cancelled, MemoryError).
void runLongImpl(const char* label, py::handle progress,
                 const std::function<void(const prt::ProgressFn&)>& work);
template <class Work>
auto runLong(const char* label, py::handle progress, Work&& work) {
  using R = decltype(work(prt::ProgressFn{}));
  std::optional<R> result;
  runLongImpl(label, progress, [&](const prt::ProgressFn& p) { result.emplace(work(p)); });
  return std::move(*result);
}

// --- registration, one function per file -----------------------------------------------------

void bindMesh(py::module_& m);      // mesh.cpp: Mesh, load_mesh, occluded, intersect
void bindTransfer(py::module_& m);  // transfer.cpp: Transfer, bake, compress
void bindLight(py::module_& m);     // light.cpp: Environment, projection, SH operations
void bindRelight(py::module_& m);   // relight.cpp: relight, render, reference, validate
void bindHaar(py::module_& m);      // haar.cpp: HaarLight, project_haar, read_haar_light
void bindFiles(py::module_& m);     // files.cpp: bake files, light files, course formats, images
void bindProbes(py::module_& m);    // probes.cpp: bake_probes, relight_probes, shade_probes

}  // namespace prtpy
