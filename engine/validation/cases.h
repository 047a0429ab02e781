// Declarations of the validation cases; each is defined in its own file in this folder.
#pragma once

#include "engine/validation/case.h"

namespace fibrenet::validation {

// Beam cases (beam_cases*.cpp).
std::vector<CaseResult> AxialStretch();
std::vector<CaseResult> Torsion();
std::vector<CaseResult> CantileverSmall();
std::vector<CaseResult> CantileverElastica();
std::vector<CaseResult> EulerBuckling();
std::vector<CaseResult> BendingFrequency();

// Particle and bond cases (particle_cases*.cpp).
std::vector<CaseResult> RigidMotion();
std::vector<CaseResult> Conservation();
std::vector<CaseResult> VanWykCompression();
std::vector<CaseResult> Restitution();
std::vector<CaseResult> FrictionIncline();
std::vector<CaseResult> DragTerminalVelocity();
std::vector<CaseResult> MaxwellRelaxation();
std::vector<CaseResult> HillCriterion();

}  // namespace fibrenet::validation
