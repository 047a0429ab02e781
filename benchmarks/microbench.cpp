// Micro-benchmarks of the per-pair kernels and of one step of the fibre bed.
//   build/fibrenet_microbench [--benchmark_filter=Bond]
// Kernels run over a batch of different pairs so that nothing is folded at compile time;
// items/s is pairs (or particle-steps) per second on one thread unless stated.
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "engine/bench/fibre_bed.h"
#include "engine/core/parallel.h"
#include "engine/core/quaternion.h"
#include "engine/core/simulation.h"
#include "engine/interactions/beam_bond.h"
#include "engine/interactions/beam_bond_lanes.h"
#include "engine/interactions/contact_lanes.h"
#include "engine/interactions/contact.h"

namespace fibrenet {
namespace {

constexpr double kR = 16e-6, kL = 32e-6;
constexpr int kBatch = 1024;

Quat SmallRotation(std::mt19937& rng, double angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return QuatFromRotationVector(Vec3(u(rng), u(rng), u(rng)) * angle);
}

struct BondCase {
  BondGeometry g;
  BondState s;
};

std::vector<BondCase> BondBatch() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<BondCase> batch(kBatch);
  for (BondCase& c : batch) {
    const Quat q_i = SmallRotation(rng, 0.5), q_j = SmallRotation(rng, 0.5);
    const Vec3 axis = Vec3(1.0, 0.2 * u(rng), 0.2 * u(rng)).normalized();
    c.s = MakeBondState(kL * axis, q_i, q_j);
    c.g = {kL * axis + 1e-3 * kL * Vec3(u(rng), u(rng), u(rng)),
           SmallRotation(rng, 1e-3) * q_i,
           SmallRotation(rng, 1e-3) * q_j,
           Vec3(u(rng), u(rng), u(rng)),
           Vec3(u(rng), u(rng), u(rng)) * 1e3,
           Vec3(u(rng), u(rng), u(rng)) * 1e3};
  }
  return batch;
}

// One six-mode bond evaluation with the fibre-bed parameters: arg 0 elastic, no failure;
// arg 1 as a fibre-fibre bond in a virtual test (Hill failure, dashpots in every mode).
BeamBondParams BenchBondParams(bool hill_and_damping) {
  BeamBondParams p = BeamBondParams::FromBeam(10e9, 3e9, kR, kL);
  if (hill_and_damping) {
    p.failure = BondFailure::kHill;
    p.F_r0 = p.F_s0 = 10.0;  // [N] strong enough that no bond of the batch breaks
    p.HillDefaults();
    p.damping_n = p.damping_s = 1e-6;
    p.damping_rot = 1e-15;
  }
  return p;
}

void BM_EvaluateBond(benchmark::State& state) {
  std::vector<BondCase> batch = BondBatch();
  const BeamBondParams p = BenchBondParams(state.range(0) != 0);
  state.SetLabel(state.range(0) != 0 ? "hill+damping" : "elastic");
  const double dt = 1e-9;
  for (auto _ : state) {
    for (BondCase& c : batch) {
      const BondResult r = EvaluateBond(c.g, p, c.s, dt);
      benchmark::DoNotOptimize(r);
    }
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}
BENCHMARK(BM_EvaluateBond)->Arg(0)->Arg(1);

// The same bonds four at a time through the lanes (beam_bond_lanes.h), gathered beforehand:
// items/s is bonds per second, to compare with BM_EvaluateBond.
void BM_EvaluateBondLanes(benchmark::State& state) {
  const std::vector<BondCase> batch = BondBatch();
  const BondLanesType p = LanesTypeOf(BenchBondParams(state.range(0) != 0), 1e-9);
  std::vector<BondLanesInput> groups(kBatch / kBondLanes);
  for (std::size_t k = 0; k < groups.size(); ++k) {
    groups[k].damped = groups[k].viscous = false;
    for (int l = 0; l < kBondLanes; ++l) {
      const BondCase& c = batch[k * kBondLanes + l];
      SetLane(groups[k], l, c.g, c.s, p);
    }
  }
  state.SetLabel(state.range(0) != 0 ? "hill+damping" : "elastic");
  const double dt = 1e-9;
  BondLanesResult r;
  for (auto _ : state) {
    for (const BondLanesInput& in : groups) {
      EvaluateBondLanes(in, dt, r);
      benchmark::DoNotOptimize(r);
    }
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}
BENCHMARK(BM_EvaluateBondLanes)->Arg(0)->Arg(1);

// Touching pairs of two fibre particles, moving and spinning at random.
std::vector<ContactGeometry> ContactBatch() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<ContactGeometry> batch(kBatch);
  for (ContactGeometry& g : batch) {
    const Vec3 n = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double dist = 2.0 * kR * (0.97 + 0.02 * u(rng));
    g = {dist * n, dist, kR, kR, 4e-12, Vec3(u(rng), u(rng), u(rng)),
         Vec3(u(rng), u(rng), u(rng)) * 1e3, Vec3(u(rng), u(rng), u(rng)) * 1e3};
  }
  return batch;
}

ContactParams BenchContactParams() {
  ContactParams p;
  p.restitution = 0.5;
  p.Derive();
  return p;
}

// One van Wyk contact with damping and, for arg 1, Cundall-Strack friction with history.
void BM_EvaluateContact(benchmark::State& state) {
  const std::vector<ContactGeometry> batch = ContactBatch();
  std::vector<Vec3> history(kBatch, Vec3::Zero());
  const ContactParams p = BenchContactParams();
  const bool friction = state.range(0) != 0;
  for (auto _ : state) {
    for (int k = 0; k < kBatch; ++k) {
      const ContactResult r = EvaluateContact(batch[k], p, history[k], 1e-9, friction);
      benchmark::DoNotOptimize(r);
    }
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
  state.SetLabel(friction ? "friction" : "frictionless");
}
BENCHMARK(BM_EvaluateContact)->Arg(0)->Arg(1);

// The same contacts four at a time through the lanes (contact_lanes.h), gathered beforehand:
// items/s is contacts per second, to compare with BM_EvaluateContact.
void BM_EvaluateContactLanes(benchmark::State& state) {
  const std::vector<ContactGeometry> batch = ContactBatch();
  std::vector<ContactLanesInput> groups(kBatch / kLanes);
  const Vec3 no_history[kLanes] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  for (std::size_t k = 0; k < groups.size(); ++k)
    SetContactLanes(&batch[k * kLanes], no_history, groups[k]);
  const ContactParams p = BenchContactParams();
  const bool friction = state.range(0) != 0;
  ContactLanesResult r;
  for (auto _ : state) {
    for (ContactLanesInput& in : groups) {
      EvaluateContactLanes(in, p, 1e-9, friction, r);
      in.xi = r.xi;
      benchmark::DoNotOptimize(r);
    }
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
  state.SetLabel(friction ? "friction" : "frictionless");
}
BENCHMARK(BM_EvaluateContactLanes)->Arg(0)->Arg(1);

// One full step of the fibre bed (contacts formed), arg = particles; items = particle-steps.
void BM_Step(benchmark::State& state) {
  World w;
  bench::FibreBedSpec spec;
  spec.particles = state.range(0);
  bench::BuildFibreBed(spec, w);
  Simulation sim(w);
  sim.Prepare();
  sim.Run(100);  // the layers land
  for (auto _ : state) sim.Step();
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(w.particles.size()));
  state.counters["threads"] = ThreadCount();
}
BENCHMARK(BM_Step)->Arg(10000)->Arg(50000)->Unit(benchmark::kMillisecond)->UseRealTime();

// A neighbour list build of the landed fibre bed.
void BM_NeighbourBuild(benchmark::State& state) {
  World w;
  bench::FibreBedSpec spec;
  spec.particles = state.range(0);
  bench::BuildFibreBed(spec, w);
  Simulation sim(w);
  sim.Prepare();
  sim.Run(100);
  for (auto _ : state) w.neighbours.Build(w.particles, w.cell, w.bonds, w.settings.skin);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(w.particles.size()));
}
BENCHMARK(BM_NeighbourBuild)->Arg(50000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace fibrenet

BENCHMARK_MAIN();
