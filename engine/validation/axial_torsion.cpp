#include "engine/validation/cases.h"

namespace fibrenet::validation {

std::vector<CaseResult> AxialStretch() { return {Finish({"AxialStretch", "none", true, 1.0, 0.0})}; }
std::vector<CaseResult> Torsion() { return {Finish({"Torsion", "none", true, 1.0, 0.0})}; }

}  // namespace fibrenet::validation
