#include "common.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <sstream>
#include <thread>

namespace prtpy {

// --- errors --------------------------------------------------------------------------------

void registerExceptions(py::module_& m) {
  // Translators are tried newest first: Cancelled before its base.
  auto& error = py::register_exception<prt::Error>(m, "Error", PyExc_RuntimeError);
  error.doc() =
      "An error of the prtkit library: a file that cannot be read, settings it refuses, a "
      "computation that fails. The message is the library's one line (it names the file).";
  auto& cancelled = py::register_exception<prt::Cancelled>(m, "Cancelled", error.ptr());
  cancelled.doc() = "A long operation was cancelled (its progress callback returned False).";
}

void warn(const std::string& message) {
  if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) != 0) throw py::error_already_set();
}

// --- arrays in -----------------------------------------------------------------------------

namespace {

std::string shapeText(const py::ssize_t* dims, py::ssize_t ndim) {
  std::string s = "(";
  for (py::ssize_t k = 0; k < ndim; ++k) {
    if (k) s += ", ";
    s += std::to_string(dims[k]);
  }
  return s + (ndim == 1 ? ",)" : ")");
}

std::string patternText(const Shape& shape) {
  static const char* names[] = {"N", "M", "K", "L"};
  std::string s = "(";
  int unnamed = 0;
  for (std::size_t k = 0; k < shape.size(); ++k) {
    if (k) s += ", ";
    s += shape[k] == kAny ? names[std::min(unnamed++, 3)] : std::to_string(shape[k]);
  }
  return s + (shape.size() == 1 ? ",)" : ")");
}

std::string dtypeName(const py::array& a) {
  return py::str(a.dtype()).cast<std::string>();
}

/// `obj` as a numpy array (lists and buffer objects converted), any dtype.
py::array anyArray(py::handle obj, const char* what) {
  if (obj.is_none()) throw py::value_error(std::string(what) + " is None (expected an array)");
  py::array a = py::array::ensure(obj);
  if (!a) throw py::value_error(std::string(what) + " is not an array of numbers");
  return a;
}

void requireReal(const py::array& a, const char* what) {
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::value_error(std::string(what) + " must hold real numbers (got dtype " + dtypeName(a) +
                          ")");
}

void requireShape(const py::array& a, const char* what, const Shape& shape) {
  bool ok = static_cast<std::size_t>(a.ndim()) == shape.size();
  for (std::size_t k = 0; ok && k < shape.size(); ++k)
    ok = shape[k] == kAny || shape[k] == a.shape(static_cast<py::ssize_t>(k));
  if (!ok)
    throw py::value_error(std::string(what) + " must have shape " + patternText(shape) + ", got " +
                          shapeText(a.shape(), a.ndim()));
}

template <class T>
void requireFiniteT(const T* data, std::size_t n, const char* what, const py::ssize_t* dims,
                    py::ssize_t ndim) {
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isfinite(data[i])) continue;
    // The multi-index of element i, for the message.
    std::vector<std::size_t> idx(static_cast<std::size_t>(ndim));
    std::size_t rest = i;
    for (py::ssize_t k = ndim - 1; k >= 0; --k) {
      const std::size_t d = static_cast<std::size_t>(dims[k]);
      idx[static_cast<std::size_t>(k)] = d ? rest % d : 0;
      rest = d ? rest / d : 0;
    }
    std::string at = "[";
    for (std::size_t k = 0; k < idx.size(); ++k) at += (k ? ", " : "") + std::to_string(idx[k]);
    throw py::value_error(std::string(what) + " holds " +
                          (std::isnan(data[i]) ? "NaN" : "an infinity") + " at " + at + "]" +
                          (ndim == 0 ? "" : " (values must be finite)"));
  }
}

}  // namespace

void requireFinite(const float* data, std::size_t n, const char* what, const Shape& shape) {
  requireFiniteT(data, n, what, shape.data(), static_cast<py::ssize_t>(shape.size()));
}

py::array_t<float, py::array::c_style> floats(py::handle obj, const char* what, const Shape& shape,
                                              bool allowNonFinite) {
  const py::array a = anyArray(obj, what);
  requireReal(a, what);
  requireShape(a, what, shape);
  auto out = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!out) throw py::error_already_set();
  if (!allowNonFinite)
    requireFiniteT(out.data(), static_cast<std::size_t>(out.size()), what, out.shape(), out.ndim());
  return out;
}

py::array_t<double, py::array::c_style> doubles(py::handle obj, const char* what,
                                                const Shape& shape, bool allowNonFinite) {
  const py::array a = anyArray(obj, what);
  requireReal(a, what);
  requireShape(a, what, shape);
  auto out = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!out) throw py::error_already_set();
  if (!allowNonFinite)
    requireFiniteT(out.data(), static_cast<std::size_t>(out.size()), what, out.shape(), out.ndim());
  return out;
}

py::array inPlaceFloats(py::handle obj, const char* what) {
  if (!py::isinstance<py::array>(obj))
    throw py::value_error(std::string(what) + " must be a numpy array (got " +
                          py::str(py::type::of(obj)).cast<std::string>() + ")");
  py::array a = py::reinterpret_borrow<py::array>(obj);
  const std::string fix =
      " (it is read in place, never converted: np.ascontiguousarray(x, dtype=np.float32) makes "
      "such a copy)";
  if (!a.dtype().is(py::dtype::of<float>()))
    throw py::value_error(std::string(what) + " must be float32, got " + dtypeName(a) + fix);
  if (!(a.flags() & py::array::c_style))
    throw py::value_error(std::string(what) + " must be C-contiguous, got a strided view" + fix);
  if (a.ndim() < 2 || a.ndim() > 4)
    throw py::value_error(std::string(what) + " must have 2 to 4 dimensions, got shape " +
                          shapeText(a.shape(), a.ndim()));
  return a;
}

std::vector<std::array<std::uint32_t, 3>> triangles(py::handle obj, const char* what,
                                                    std::size_t limit) {
  const py::array a = anyArray(obj, what);
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::value_error(std::string(what) + " must hold integer vertex indices (got dtype " +
                          dtypeName(a) + ")");
  requireShape(a, what, {kAny, 3});
  auto idx = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!idx) throw py::error_already_set();
  const long long* p = idx.data();
  const std::size_t n = static_cast<std::size_t>(idx.shape(0));
  std::vector<std::array<std::uint32_t, 3>> out(n);
  for (std::size_t t = 0; t < n; ++t)
    for (int c = 0; c < 3; ++c) {
      const long long v = p[3 * t + c];
      if (v < 0 || static_cast<unsigned long long>(v) >= limit)
        throw py::value_error(std::string(what) + "[" + std::to_string(t) + "] references vertex " +
                              std::to_string(v) + " (the mesh has " + std::to_string(limit) +
                              " vertices)");
      out[t][c] = static_cast<std::uint32_t>(v);
    }
  return out;
}

std::vector<std::uint32_t> indices(py::handle obj, const char* what, std::size_t limit) {
  const py::array a = anyArray(obj, what);
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::value_error(std::string(what) + " must hold integer indices (got dtype " +
                          dtypeName(a) + ")");
  requireShape(a, what, {kAny});
  auto idx = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!idx) throw py::error_already_set();
  std::vector<std::uint32_t> out(static_cast<std::size_t>(idx.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const long long v = idx.data()[i];
    if (v < 0 || static_cast<unsigned long long>(v) >= limit)
      throw py::value_error(std::string(what) + "[" + std::to_string(i) +
                            "] = " + std::to_string(v) + " is out of range (0.." +
                            std::to_string(limit == 0 ? 0 : limit - 1) + ")");
    out[i] = static_cast<std::uint32_t>(v);
  }
  return out;
}

prt::Vec3f vec3(py::handle obj, const char* what) {
  const auto a = doubles(obj, what, {3});
  return prt::Vec3f(prt::Vec3d(a.data()[0], a.data()[1], a.data()[2]));
}

prt::Rgb rgb(py::handle obj, const char* what) {
  const py::array a = anyArray(obj, what);
  if (a.ndim() == 0) {
    const auto g = doubles(obj, what, {});
    return prt::Rgb(static_cast<float>(g.data()[0]));
  }
  return vec3(obj, what);
}

std::vector<prt::Rgb> albedoOf(py::handle obj, std::size_t rows) {
  const py::array a = py::array::ensure(obj);
  if (a && a.ndim() == 2) {
    const auto al = floats(obj, "albedo", {static_cast<py::ssize_t>(rows), 3});
    std::vector<prt::Rgb> out(rows);
    std::memcpy(static_cast<void*>(out.data()), al.data(), rows * sizeof(prt::Rgb));
    return out;
  }
  return {rgb(obj, "albedo")};
}

bool isPath(py::handle obj) {
  return py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__");
}

std::string pathString(py::handle obj) {
  return py::str(py::module_::import("os").attr("fspath")(obj)).cast<std::string>();
}

prt::Mat3d rotation(py::handle obj, const char* what) {
  if (obj.is_none()) return prt::Mat3d::identity();
  const py::array a = anyArray(obj, what);
  if (a.ndim() == 1) {
    const auto e = doubles(obj, what, {3});
    return prt::rotationEulerXYZ(e.data()[0], e.data()[1], e.data()[2]);
  }
  if (a.ndim() != 2)
    throw py::value_error(std::string(what) +
                          " must be a 3x3 rotation matrix or three Euler angles in degrees (X, "
                          "Y, Z), got shape " +
                          shapeText(a.shape(), a.ndim()));
  const auto r = doubles(obj, what, {3, 3});
  prt::Mat3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.m[i][j] = r.data()[3 * i + j];
  // SH rotation assumes a rotation: orthonormal with determinant +1.
  const prt::Mat3d p = m.transposed() * m;
  double off = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) off = std::max(off, std::abs(p.m[i][j] - (i == j ? 1.0 : 0.0)));
  const double det = m.m[0][0] * (m.m[1][1] * m.m[2][2] - m.m[1][2] * m.m[2][1]) -
                     m.m[0][1] * (m.m[1][0] * m.m[2][2] - m.m[1][2] * m.m[2][0]) +
                     m.m[0][2] * (m.m[1][0] * m.m[2][1] - m.m[1][1] * m.m[2][0]);
  if (off > 1e-4 || det < 0)
    throw py::value_error(std::string(what) +
                          " is not a rotation (it must be orthonormal with determinant +1)");
  return m;
}

prt::sh::RgbSh light(py::handle obj, const char* what) {
  const auto a = floats(obj, what, {kAny, 3});
  const std::size_t n = static_cast<std::size_t>(a.shape(0));
  const int b = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n))));
  if (n == 0 || static_cast<std::size_t>(b) * static_cast<std::size_t>(b) != n)
    throw py::value_error(std::string(what) + " must have B² rows (1, 4, 9, 16, ...), got " +
                          std::to_string(n));
  if (b > prt::sh::kMaxBands)
    throw py::value_error(std::string(what) + " has " + std::to_string(b) + " bands (at most " +
                          std::to_string(prt::sh::kMaxBands) + ")");
  prt::sh::RgbSh out(b);
  for (std::size_t i = 0; i < n; ++i)
    out.c[i] = prt::Rgb(a.data()[3 * i], a.data()[3 * i + 1], a.data()[3 * i + 2]);
  return out;
}

// --- arrays out ----------------------------------------------------------------------------

py::capsule capsule(std::unique_ptr<Buffer> buffer) {
  return py::capsule(buffer.release(), kBufferCapsule, [](PyObject* o) {
    delete static_cast<Buffer*>(PyCapsule_GetPointer(o, kBufferCapsule));
  });
}

py::array view(py::dtype dtype, const Shape& shape, const void* data, py::handle base,
               bool writable) {
  py::array a(dtype, shape, {}, data, base);
  if (!writable)
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::array lightArray(const prt::sh::RgbSh& light) {
  return adoptVector(light.c, {static_cast<py::ssize_t>(light.c.size()), 3});
}

std::shared_ptr<const void> keepAlive(py::object obj) {
  return std::shared_ptr<const void>(new py::object(std::move(obj)), [](const py::object* o) {
    py::gil_scoped_acquire gil;
    delete o;
  });
}

// --- long calls ----------------------------------------------------------------------------

namespace {

/// The progress callback as the user gave it (None, True, a callable), called with the GIL.
class Reporter {
 public:
  Reporter(py::handle progress, const char* label) {
    if (progress.is_none() || progress.ptr() == Py_False) return;
    if (progress.ptr() == Py_True) {
      py::object bar = py::module_::import("prtkit._progress").attr("bar")(label);
      if (!bar.is_none()) fn_ = std::move(bar);
      return;
    }
    if (!PyCallable_Check(progress.ptr()))
      throw py::type_error(
          "progress must be None, True (a tqdm bar) or a callable taking the fraction done");
    fn_ = py::reinterpret_borrow<py::object>(progress);
  }
  explicit operator bool() const { return bool(fn_); }
  /// False when the callback returned False (cancel).
  bool report(double fraction) {
    last_ = fraction;
    return fn_(fraction).ptr() != Py_False;
  }
  double last() const { return last_; }
  void close() {
    if (fn_ && py::hasattr(fn_, "close")) fn_.attr("close")();
  }

 private:
  py::object fn_;
  double last_ = -1;
};

struct Shared {
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  std::exception_ptr error;
  std::atomic<double> fraction{0.0};
  std::atomic<bool> cancel{false};
};

constexpr auto kPoll = std::chrono::milliseconds(50);

/// The long calls in progress, so that Ctrl-C stops all of them (as in prt): the process-wide
/// cancel flag it sets stays set until the last of them has finished.
std::mutex gCallsMutex;
int gCalls = 0;
bool gInterrupted = false;

struct ActiveCall {
  ActiveCall() {
    std::lock_guard<std::mutex> lock(gCallsMutex);
    ++gCalls;
  }
  ~ActiveCall() {
    std::lock_guard<std::mutex> lock(gCallsMutex);
    if (--gCalls == 0 && gInterrupted) {
      prt::clearCancel();
      gInterrupted = false;
    }
  }
  static void interrupt() {
    std::lock_guard<std::mutex> lock(gCallsMutex);
    gInterrupted = true;
    prt::requestCancel();
  }
};

}  // namespace

void runLongImpl(const char* label, py::handle progress,
                 const std::function<void(const prt::ProgressFn&)>& work) {
  Reporter reporter(progress, label);
  const ActiveCall active;
  auto shared = std::make_shared<Shared>();
  const prt::ProgressFn fn = [shared](double f) {
    shared->fraction.store(f, std::memory_order_relaxed);
    return !shared->cancel.load(std::memory_order_relaxed);
  };
  std::thread worker([shared, &work, &fn] {
    try {
      work(fn);
    } catch (...) {
      shared->error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(shared->m);
      shared->done = true;
    }
    shared->cv.notify_all();
  });

  std::optional<py::error_already_set> pythonError;  // from a signal handler or the callback
  for (;;) {
    bool done;
    {
      py::gil_scoped_release nogil;
      std::unique_lock<std::mutex> lock(shared->m);
      done = shared->cv.wait_for(lock, kPoll, [&] { return shared->done; });
    }
    if (done) break;
    if (pythonError) continue;  // cancelling: wait for the work to stop
    if (PyErr_CheckSignals() != 0) {
      pythonError.emplace();
      shared->cancel.store(true);
      // Prompt: every Progress checks this flag at each chunk of work, not only when it next
      // calls back (every 1/256th). It is process-wide, as in the CLI: Ctrl-C stops every
      // prtkit call in progress (ActiveCall clears it when the last has stopped).
      ActiveCall::interrupt();
      continue;
    }
    const double f = shared->fraction.load(std::memory_order_relaxed);
    if (reporter && f != reporter.last()) {
      try {
        if (!reporter.report(f)) shared->cancel.store(true);
      } catch (py::error_already_set& e) {
        pythonError.emplace(std::move(e));
        shared->cancel.store(true);
      }
    }
  }
  {
    py::gil_scoped_release nogil;
    worker.join();
  }
  if (!pythonError && !shared->error && reporter && reporter.last() < 1.0) {
    try {
      reporter.report(1.0);
    } catch (py::error_already_set& e) {
      pythonError.emplace(std::move(e));
    }
  }
  if (reporter) reporter.close();
  if (pythonError) throw std::move(*pythonError);
  if (shared->error) std::rethrow_exception(shared->error);
}

}  // namespace prtpy
