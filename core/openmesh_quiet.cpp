#include "openmesh_quiet.h"

#include <iostream>

#include <OpenMesh/Core/System/omstream.hh>

namespace shadowcts {
namespace {

std::recursive_mutex& openmesh_stream_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

// A stream buffer that drops everything written to it.
class NullBuffer : public std::streambuf {
 protected:
  int_type overflow(int_type c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize count) override { return count; }
};

NullBuffer& null_buffer() {
  static NullBuffer* buffer = new NullBuffer;  // lives as long as the streams may refer to it
  return *buffer;
}

// OpenMesh's error stream is redirected once per process: its disconnect() never frees what
// connect() allocated, so connecting per load would leak every time.
void silence_omerr_once() {
  static const bool silenced = [] {
    static std::ostream* sink = new std::ostream(&null_buffer());
    omerr().disconnect(std::cerr);
    omerr().connect(*sink);
    return true;
  }();
  (void)silenced;
}

}  // namespace

OpenMeshQuiet::OpenMeshQuiet()
    : lock_(openmesh_stream_mutex()), previous_cerr_(nullptr), previous_clog_(nullptr) {
  silence_omerr_once();
  std::cerr.flush();
  std::clog.flush();
  previous_cerr_ = std::cerr.rdbuf(&null_buffer());
  previous_clog_ = std::clog.rdbuf(&null_buffer());
}

OpenMeshQuiet::~OpenMeshQuiet() {
  omerr().flush();
  std::cerr.rdbuf(previous_cerr_);
  std::clog.rdbuf(previous_clog_);
}

}  // namespace shadowcts
