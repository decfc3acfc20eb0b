#pragma once
// `shadowcts check`: an engine's own result for a case's frame (the manifest's "result": a
// hard-shadow mask, a soft visibility or light lists), read and validated up front, then offered
// to the runner as one more Algorithm (id "frame", backend "external", one variant named after
// the result kind) so that it is judged exactly like a registered algorithm's output.
#include <iosfwd>
#include <memory>
#include <string>

#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"

namespace shadowcts {

// Reads c.external_result against the case's camera and ranged lights. Throws InputError naming
// the file, the channel or JSON element and the pixel: a missing or extra channel, a size that is
// not the camera's, NaN, a value outside [0, 1], a light index out of range, a list count that
// does not match the grid. Nothing is written.
std::unique_ptr<Algorithm> load_external_result(const Case& c);

// `shadowcts check --case MANIFEST --out DIR`: loads the case and its result, then runs the
// runner on that one case with a registry holding only the external result. Exit codes as
// run_suite's; InputError / UsageError before anything is written.
int check_frame(const std::string& manifest, const std::string& out_dir, bool progress,
                std::ostream& out, std::ostream& err);

}  // namespace shadowcts
