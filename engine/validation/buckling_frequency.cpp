#include "engine/validation/cases.h"

namespace fibrenet::validation {

std::vector<CaseResult> EulerBuckling() { return {Finish({"EulerBuckling", "none", true, 1.0, 0.0})}; }
std::vector<CaseResult> BendingFrequency() { return {Finish({"BendingFrequency", "none", true, 1.0, 0.0})}; }

}  // namespace fibrenet::validation
