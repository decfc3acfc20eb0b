#include "mesh_file_loader.h"

// MeshIO.hh registers OpenMesh's readers with its IOManager.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/reader/OFFReader.hh>
#include <OpenMesh/Core/IO/reader/PLYReader.hh>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <locale>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "face_keeping_importer.h"
#include "mesh_prechecks.h"
#include "openmesh_quiet.h"
#include "shadowcts/closed_surface.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

// The numbers the OFF and PLY readers extract with `stream >> value`, one whole word each and
// checked as a value of its kind. A standard read stops inside a word ("1,5", "0.5x", "1.5" where
// a count belongs) and leaves the rest of it to the next read, which takes it for the next value;
// and it reads "1e-400" as 0 and "-1" as a count of 4294967295. Here the word is read by the
// standard extraction and fails unless all of it is read and it is a plain number of its kind.
class CheckedNumbers final : public std::num_get<char> {
 protected:
  template <typename T, typename Accept>
  iter_type word(iter_type in, iter_type end, std::ios_base::iostate& err, T& value,
                 Accept accept) const {
    std::string text;
    for (; in != end && !std::isspace(static_cast<unsigned char>(*in)); ++in) text.push_back(*in);
    // One stream per thread, reused: a new stream for each number costs more than reading it.
    thread_local std::istringstream read = [] {
      std::istringstream stream;
      stream.imbue(std::locale::classic());
      return stream;
    }();
    read.clear();
    read.str(text);
    if (!(read >> value) || read.peek() != std::char_traits<char>::eof() || !accept(text))
      err |= std::ios_base::failbit;
    if (in == end) err |= std::ios_base::eofbit;
    return in;
  }
  static bool digits(std::string_view text) {
    return !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
  }
  iter_type do_get(iter_type in, iter_type end, std::ios_base&, std::ios_base::iostate& err,
                   unsigned int& value) const override {
    return word(in, end, err, value, [](const std::string& text) { return digits(text); });
  }
  iter_type do_get(iter_type in, iter_type end, std::ios_base&, std::ios_base::iostate& err,
                   long& value) const override {  // what `>> int` reads
    return word(in, end, err, value, [](const std::string& text) {
      return digits(std::string_view(text).substr(text[0] == '+' || text[0] == '-' ? 1 : 0));
    });
  }
  iter_type do_get(iter_type in, iter_type end, std::ios_base&, std::ios_base::iostate& err,
                   float& value) const override {
    return word(in, end, err, value, [](const std::string& text) { return !float_problem(text); });
  }
  iter_type do_get(iter_type in, iter_type end, std::ios_base&, std::ios_base::iostate& err,
                   double& value) const override {
    return word(in, end, err, value, [](const std::string& text) { return !float_problem(text); });
  }
};

// OFF and PLY through OpenMesh's readers, from a stream that throws on the first failed read:
// their loops over declared counts then end where the file does, and a value that does not parse
// is named (by the importer) instead of leaving the rest of the file unread or misread. The PLY
// reader parses its header again from the stream; the OFF reader takes its options (binary,
// normals, colours) from the keyword line, read by can_u_read.
bool read_through_throwing_stream(const std::string& path, bool off, std::istream& stream,
                                  FaceKeepingImporter& importer) {
  OpenMesh::IO::Options options;
  if (off && !OpenMesh::IO::OFFReader().can_u_read(path)) return false;
  stream.imbue(std::locale(std::locale::classic(), new CheckedNumbers));
  stream.exceptions(std::ios::failbit | std::ios::badbit);
  bool read_ok = false;
  try {
    read_ok = off ? OpenMesh::IO::OFFReader().read(stream, importer, options)
                  : OpenMesh::IO::PLYReader().read(stream, importer, options);
  } catch (const std::ios_base::failure&) {
    // The OFF reader reads the rest of the line after each face (its colour): at the end of a
    // file without a final newline that read fails after every face was delivered.
    const bool after_the_last_face = off && stream.eof() && importer.declared_faces &&
                                     importer.faces_read == *importer.declared_faces;
    if (!after_the_last_face) importer.read_failed();
    read_ok = true;
  }
  // The readers also stop, without a failed read, where the end of the file comes right after a
  // value (their loops test eof()).
  importer.require_declared_counts();
  return read_ok;
}

// The words of a list, quoted, the first four of them.
std::string quoted_list(const std::vector<std::string>& words) {
  std::string list;
  for (std::size_t i = 0; i < words.size() && i < 4; ++i)
    list += (list.empty() ? "'" : ", '") + words[i] + "'";
  if (words.size() > 4) list += ", ... (" + std::to_string(words.size()) + " words)";
  return list;
}

}  // namespace

LoadedScene load_mesh_file(const std::string& path) {
  const std::filesystem::path file(path);
  std::string format = file.extension().string();
  std::transform(format.begin(), format.end(), format.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // What OpenMesh's readers would crash on or misread without a failed read (mesh_prechecks.h).
  const DeclaredCounts declared = precheck_mesh_file(path, format);

  const bool through_stream = format == ".off" || format == ".ply";
  std::ifstream stream;
  if (through_stream) stream.open(path, std::ios::binary);
  FaceKeepingImporter importer(path, through_stream ? &stream : nullptr, !declared.binary);
  bool read_ok = false;
  {
    const OpenMeshQuiet quiet;
    OpenMesh::IO::Options options;
    try {
      read_ok = through_stream
                    ? read_through_throwing_stream(path, format == ".off", stream, importer)
                    : OpenMesh::IO::IOManager().read(path, importer, options);
    } catch (const std::exception& e) {
      throw InputError(path, "file", std::string("OpenMesh failed: ") + e.what());
    }
  }
  if (importer.problem) throw InputError(path, importer.problem->first, importer.problem->second);
  if (!read_ok) throw InputError(path, "file", "OpenMesh cannot read it as a " + format + " file");
  // Faces that repeat a corner: the OBJ and STL readers drop them before the importer sees them,
  // so their pre-checks count and name them; the others hand them over.
  const std::size_t repeated_vertex_faces =
      std::max(importer.repeated_vertex_faces, declared.repeated_vertex_faces);
  const std::optional<std::string> first_repeated_vertex = declared.first_repeated_vertex
                                                               ? declared.first_repeated_vertex
                                                               : importer.first_repeated_vertex;
  if (importer.face_corners.empty()) {
    // OpenMesh "loads" an invalid file as an empty mesh: empty is an error.
    const std::size_t faces = std::max(importer.faces_read, declared.faces);
    if (faces > 0 && repeated_vertex_faces == faces) {
      throw InputError(path, "faces",
                       "every face (" + std::to_string(faces) +
                           ") repeats a vertex, so none has area (first: " +
                           first_repeated_vertex.value_or("?") + ")");
    }
    throw InputError(path, "faces", "no faces: empty, or not a valid " + format + " file");
  }
  const auto declared_vertices = through_stream ? importer.declared_vertices : declared.vertices;
  if (declared_vertices && importer.points.size() < *declared_vertices) {
    throw InputError(path, "vertices",
                     "the file declares " + std::to_string(*declared_vertices) +
                         " vertices, OpenMesh read " + std::to_string(importer.points.size()));
  }

  LoadedScene scene;
  scene.triangles = importer.triangles();
  if (repeated_vertex_faces > 0) {
    scene.warnings.push_back(path + ": faces: " + std::to_string(repeated_vertex_faces) +
                             " face(s) with a repeated vertex dropped (no area, no shadow)" +
                             (first_repeated_vertex ? "; first: " + *first_repeated_vertex : ""));
  }
  const std::size_t dropped_triangles =
      std::max(importer.repeated_vertex_triangles, declared.repeated_vertex_faces);
  if (declared.triangles && scene.triangles.size() + dropped_triangles < *declared.triangles) {
    scene.warnings.push_back(path + ": faces: the file has " + std::to_string(*declared.triangles) +
                             " triangles, OpenMesh read " + std::to_string(scene.triangles.size()));
  }
  if (!declared.skipped_words.empty()) {
    scene.warnings.push_back(path + ": header: words the reader does not know, skipped: " +
                             quoted_list(declared.skipped_words));
  }

  Mesh loaded_mesh;
  loaded_mesh.name = file.stem().string();
  loaded_mesh.closed = is_closed_surface(scene.triangles);
  scene.meshes.push_back(std::move(loaded_mesh));
  return scene;
}

}  // namespace shadowcts
