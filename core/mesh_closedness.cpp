#include "mesh_closedness.h"

#include <iostream>

#include <OpenMesh/Core/System/omstream.hh>

namespace shadowcts {

namespace {
std::recursive_mutex& openmesh_error_stream_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

// OpenMesh's error stream is redirected once per process, into one buffer: its disconnect()
// never frees what connect() allocated, so connecting per load would leak every time.
std::ostringstream& openmesh_error_buffer() {
  static std::ostringstream* buffer = [] {
    auto* b = new std::ostringstream;  // lives as long as OpenMesh's stream refers to it
    omerr().disconnect(std::cerr);
    omerr().connect(*b);
    return b;
  }();
  return *buffer;
}
}  // namespace

OpenMeshErrorCapture::OpenMeshErrorCapture()
    : lock_(openmesh_error_stream_mutex()), previous_cerr_(nullptr), previous_clog_(nullptr) {
  omerr().flush();
  openmesh_error_buffer().str("");
  std::cerr.flush();
  std::clog.flush();
  previous_cerr_ = std::cerr.rdbuf(openmesh_error_buffer().rdbuf());
  previous_clog_ = std::clog.rdbuf(openmesh_error_buffer().rdbuf());
}

OpenMeshErrorCapture::~OpenMeshErrorCapture() {
  omerr().flush();
  std::cerr.rdbuf(previous_cerr_);
  std::clog.rdbuf(previous_clog_);
  openmesh_error_buffer().str("");
}

std::string OpenMeshErrorCapture::text() {
  omerr().flush();
  std::cerr.flush();
  std::clog.flush();
  return openmesh_error_buffer().str();
}

}  // namespace shadowcts
