#include "engine/validation/cases.h"

namespace fibrenet::validation {

std::vector<CaseResult> CantileverSmall() { return {Finish({"CantileverSmall", "none", true, 1.0, 0.0})}; }
std::vector<CaseResult> CantileverElastica() { return {Finish({"CantileverElastica", "none", true, 1.0, 0.0})}; }

}  // namespace fibrenet::validation
