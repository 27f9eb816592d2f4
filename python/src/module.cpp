// The prtkit Python module (_prtkit, imported by prtkit/__init__.py): the library from Python,
// numpy in and out. One file per concept: mesh.cpp, transfer.cpp, light.cpp, relight.cpp,
// files.cpp; what they share is common.hpp and objects.hpp.

#include <memory>

#include "common.hpp"
#include "prt/core/parallel.hpp"
#include "prt/core/version.hpp"

namespace {

std::unique_ptr<prt::ThreadLimit>& threadLimit() {
  static std::unique_ptr<prt::ThreadLimit> limit;
  return limit;
}

}  // namespace

PYBIND11_MODULE(_prtkit, m) {
  namespace py = pybind11;
  m.doc() = "prtkit: precomputed radiance transfer (the C++ library's Python binding)";
  m.attr("__version__") = prt::kVersion;
  prtpy::registerExceptions(m);
  prtpy::bindMesh(m);
  prtpy::bindTransfer(m);
  prtpy::bindLight(m);
  prtpy::bindRelight(m);
  prtpy::bindHaar(m);
  prtpy::bindFiles(m);
  prtpy::bindProbes(m);

  m.def(
      "set_threads",
      [](int threads) {
        if (threads < 0 || threads > 4096) throw py::value_error("threads must be 0..4096");
        threadLimit().reset();
        if (threads > 0) threadLimit() = std::make_unique<prt::ThreadLimit>(threads);
      },
      py::arg("threads"),
      "Limits the worker threads of every later call (0: all cores, the default), as `prt -j`. "
      "Results do not depend on it.");
  m.def("get_threads", &prt::maxThreads, "The number of threads a parallel call may use now.");
  m.def(
      "_buffer_address",
      [](py::capsule c) {
        if (!c.name() || std::string(c.name()) != prtpy::kBufferCapsule)
          throw py::value_error("not a prtkit result buffer");
        return reinterpret_cast<std::uintptr_t>(c.get_pointer<prtpy::Buffer>()->data);
      },
      py::arg("capsule"),
      "The address of the C++ buffer a result array's capsule owns (to check that no copy was "
      "made).");
}
