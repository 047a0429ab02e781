// Bonds in structure-of-arrays form: endpoints, parameter set, and per-bond state (rest
// configuration and history). Bonds are removed by marking them broken; the arrays keep
// their order so that bond ids stay valid for events and snapshots.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/interactions/beam_bond.h"

namespace fibrenet {

// kAdhesive: a sheet particle held to a fixed anchor on a surface (the Yankee coating).
enum class BondKind : std::uint8_t { kFibre = 0, kFibreFibre = 1, kAdhesive = 2 };

// A broken bond, kept for analysis.
struct BondBreakEvent {
  std::int64_t step = 0;
  std::int32_t bond = 0;
  Vec3 position = Vec3::Zero();  // bond midpoint [m]
  // Share of the failure index from each mode: normal, shear, bending, twist.
  double f_r = 0.0, f_s = 0.0, tau_b = 0.0, tau_t = 0.0;
  double energy = 0.0;  // strain energy released [J]
};

struct Bonds {
  std::vector<std::int32_t> i, j;
  std::vector<std::int32_t> type;  // index into the parameter table
  std::vector<BondKind> kind;
  std::vector<BondState> state;
  std::vector<std::uint8_t> broken;
  // Per bond, only once quasi-static damping has sized the dashpots for each pair
  // (AddBondDamping); empty: every factor 1, and a run without dashpots stores nothing.
  std::vector<BondDampingFactors> damping_factors;
  std::vector<BeamBondParams> types;  // parameter table
  std::vector<BondBreakEvent> events;

  std::size_t size() const { return i.size(); }

  std::int32_t AddType(const BeamBondParams& p) {
    types.push_back(p);
    return static_cast<std::int32_t>(types.size() - 1);
  }

  std::size_t Add(std::int32_t a, std::int32_t b, std::int32_t type_id, BondKind k,
                  const BondState& s) {
    i.push_back(a);
    j.push_back(b);
    type.push_back(type_id);
    kind.push_back(k);
    state.push_back(s);
    broken.push_back(0);
    if (!damping_factors.empty()) damping_factors.emplace_back();
    return i.size() - 1;
  }

  BondDampingFactors DampingFactors(std::size_t b) const {
    return damping_factors.empty() ? BondDampingFactors{} : damping_factors[b];
  }

  std::size_t CountIntact() const {
    std::size_t n = 0;
    for (auto b : broken) n += (b == 0);
    return n;
  }
};

}  // namespace fibrenet
