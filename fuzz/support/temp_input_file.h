#pragma once
// Loader fuzz targets hand their input to the loaders as a file: the loaders take paths and
// dispatch on the extension, exactly as users call them.
#include <cstddef>
#include <cstdint>
#include <string>

namespace shadowcts::fuzzing {

// A per-process scratch folder under the system temp folder, created on first use. Files the
// loaders might look for beside their input (a glTF's .bin, a manifest's scene file) are
// resolved there.
const std::string& scratch_folder();

// Writes `data` to <scratch_folder>/<name> (replacing it) and returns the path.
std::string write_scratch_file(const std::string& name, const std::uint8_t* data, std::size_t size);

}  // namespace shadowcts::fuzzing
