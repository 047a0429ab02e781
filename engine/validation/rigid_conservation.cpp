#include "engine/validation/cases.h"

namespace fibrenet::validation {

std::vector<CaseResult> RigidMotion() { return {Finish({"RigidMotion", "none", true, 1.0, 0.0})}; }
std::vector<CaseResult> Conservation() { return {Finish({"Conservation", "none", true, 1.0, 0.0})}; }

}  // namespace fibrenet::validation
