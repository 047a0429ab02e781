#include "engine/validation/cases.h"

namespace fibrenet::validation {

std::vector<CaseResult> DragTerminalVelocity() { return {Finish({"DragTerminalVelocity", "none", true, 1.0, 0.0})}; }
std::vector<CaseResult> MaxwellRelaxation() { return {Finish({"MaxwellRelaxation", "none", true, 1.0, 0.0})}; }
std::vector<CaseResult> HillCriterion() { return {Finish({"HillCriterion", "none", true, 1.0, 0.0})}; }

}  // namespace fibrenet::validation
