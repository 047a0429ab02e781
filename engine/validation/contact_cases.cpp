#include "engine/validation/cases.h"

namespace fibrenet::validation {

std::vector<CaseResult> VanWykCompression() { return {Finish({"VanWykCompression", "none", true, 1.0, 0.0})}; }
std::vector<CaseResult> Restitution() { return {Finish({"Restitution", "none", true, 1.0, 0.0})}; }
std::vector<CaseResult> FrictionIncline() { return {Finish({"FrictionIncline", "none", true, 1.0, 0.0})}; }

}  // namespace fibrenet::validation
