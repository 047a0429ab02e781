#include "engine/io/snapshot.h"

#include <filesystem>
#include <fstream>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/simulation.h"
#include "engine/io/hdf5_file.h"

namespace fibrenet {
namespace {

// A few bonded fibres falling onto a floor with friction: every kind of state is present
// (bond frames, dashpot and plastic history, contact and wall histories, broken bonds).
World FallingFibres() {
  World w;
  w.cell.lo = Vec3(0, 0, 0);
  w.cell.hi = Vec3(0.3e-3, 0.3e-3, 1e-3);
  w.physics.gravity = true;
  w.physics.g = Vec3(0, 0, -9.81e4);
  w.physics.contacts = true;
  w.physics.friction = true;
  w.contact.restitution = 0.5;
  w.contact.Derive();
  BeamBondParams bond = BeamBondParams::FromBeam(10e9, 3e9, 16e-6, 32e-6);
  bond.maxwell_tau = 1e-5;
  bond.yield_moment = 1e-9;
  const std::int32_t type = w.bonds.AddType(bond);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int f = 0; f < 12; ++f) {
    const double angle = 2 * kPi * u(rng);
    const Vec3 dir(std::cos(angle), std::sin(angle), 0);
    // Layers 30 um apart: fibres of radius 16 um crossing each other touch from the start.
    const Vec3 start(0.3e-3 * u(rng), 0.3e-3 * u(rng), 15e-6 + 30e-6 * f);
    for (int k = 0; k < 8; ++k) {
      Vec3 x = start + 32e-6 * k * dir;
      w.cell.Wrap(x);
      w.particles.Add(x, 16e-6, 8e-12, f);
      if (k > 0) {
        const auto a = static_cast<std::int32_t>(w.particles.size() - 2), b = a + 1;
        w.bonds.Add(a, b, type, BondKind::kFibre,
                    MakeBondState(w.cell.Delta(w.particles.x[a], w.particles.x[b]),
                                  w.particles.q[a], w.particles.q[b]));
      }
    }
  }
  Wall floor;
  floor.z = 0.0;
  // Falling with some random motion so that touching pairs slide and build history.
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  for (auto& v : w.particles.v) v = Vec3(jitter(rng), jitter(rng), -0.5 + jitter(rng));
  w.walls.push_back(floor);
  return w;
}

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

TEST(Snapshot, RoundTripKeepsEveryField) {
  World w = FallingFibres();
  Simulation sim(w);
  sim.Prepare();
  sim.Run(3000);
  w.bonds.broken[3] = 1;  // a broken bond must come back broken
  w.bonds.damping_factors.resize(w.bonds.size());
  w.bonds.damping_factors[5] = {0.4f, 2.5f};
  const std::string path = TempPath("fibrenet_roundtrip.h5");
  std::vector<double> field(w.particles.size(), 1.5);
  io::WriteSnapshot(w, path, {{"strain_energy", field}});
  ASSERT_TRUE(std::filesystem::exists(TempPath("fibrenet_roundtrip.xdmf")));
  const World r = io::ReadSnapshot(path);
  ASSERT_EQ(r.particles.size(), w.particles.size());
  for (std::size_t i = 0; i < w.particles.size(); ++i) {
    EXPECT_EQ(r.particles.x[i], w.particles.x[i]);
    EXPECT_EQ(r.particles.v[i], w.particles.v[i]);
    EXPECT_EQ(r.particles.q[i].coeffs(), w.particles.q[i].coeffs());
    EXPECT_EQ(r.particles.omega[i], w.particles.omega[i]);
    EXPECT_EQ(r.particles.fibre[i], w.particles.fibre[i]);
  }
  ASSERT_EQ(r.bonds.size(), w.bonds.size());
  for (std::size_t b = 0; b < w.bonds.size(); ++b) {
    EXPECT_EQ(r.bonds.state[b].L0, w.bonds.state[b].L0);
    EXPECT_EQ(r.bonds.state[b].b_i.coeffs(), w.bonds.state[b].b_i.coeffs());
    EXPECT_EQ(r.bonds.state[b].dashpot, w.bonds.state[b].dashpot);
    EXPECT_EQ(r.bonds.state[b].plastic_y, w.bonds.state[b].plastic_y);
    EXPECT_EQ(r.bonds.DampingFactors(b).translation, w.bonds.DampingFactors(b).translation);
    EXPECT_EQ(r.bonds.DampingFactors(b).rotation, w.bonds.DampingFactors(b).rotation);
    EXPECT_EQ(r.bonds.broken[b], w.bonds.broken[b]);
  }
  EXPECT_EQ(r.bonds.types[0].maxwell_tau, w.bonds.types[0].maxwell_tau);
  EXPECT_EQ(r.step, w.step);
  EXPECT_EQ(r.time, w.time);
  EXPECT_EQ(r.walls.size(), 1u);
  EXPECT_TRUE(r.blades.empty());
  EXPECT_EQ(r.energy.work_gravity, w.energy.work_gravity);
  EXPECT_EQ(r.neighbours.ExportHistory().size(), w.neighbours.ExportHistory().size());
  std::ifstream xdmf(TempPath("fibrenet_roundtrip.xdmf"));
  const std::string text((std::istreambuf_iterator<char>(xdmf)), {});
  EXPECT_NE(text.find("fields/strain_energy"), std::string::npos);
  EXPECT_NE(text.find("Polyline"), std::string::npos);
  w.energy.overlap_regained = 2.5e-9;  // the ledger's newest term
  io::WriteSnapshot(w, path);
  EXPECT_EQ(io::ReadSnapshot(path).energy.overlap_regained, 2.5e-9);
}

// A creping frame keeps its blade: where it is, how it moves, its friction and contacts.
TEST(Snapshot, ABladeComesBackWhereItWas) {
  World w = FallingFibres();
  Blade blade = Blade::AtAngle(Vec3(1e-4, 0.0, 2e-6), 1.3);
  blade.velocity = Vec3(-30.0, 0.0, 0.0);
  blade.mu = 0.8;
  blade.hard_stiffness = 1.2e5;
  blade.work = 3e-7;
  blade.reaction = Vec3(1e-3, -2e-4, 5e-4);
  blade.history.assign(w.particles.size(), Vec3::Zero());
  blade.history[2] = Vec3(1e-7, 0.0, -3e-8);
  w.blades.push_back(blade);
  w.blades.push_back(Blade::AtAngle(Vec3::Zero(), 1.5));  // friction off, the contacts' mu
  w.blades.back().friction = false;
  const std::string path = TempPath("fibrenet_blade.h5");
  io::WriteSnapshot(w, path);
  const World r = io::ReadSnapshot(path);
  ASSERT_EQ(r.blades.size(), 2u);
  const Blade& b = r.blades[0];
  EXPECT_EQ(b.tip, blade.tip);
  EXPECT_EQ(b.face_normal, blade.face_normal);
  EXPECT_EQ(b.face_up, blade.face_up);
  EXPECT_EQ(b.velocity, blade.velocity);
  EXPECT_TRUE(b.friction);
  EXPECT_EQ(b.mu, std::optional<double>(0.8));
  EXPECT_EQ(b.hard_stiffness, blade.hard_stiffness);
  EXPECT_EQ(b.hard_gap, blade.hard_gap);
  EXPECT_EQ(b.work, blade.work);
  EXPECT_EQ(b.reaction, blade.reaction);
  EXPECT_EQ(b.history, blade.history);
  EXPECT_FALSE(r.blades[1].friction);
  EXPECT_FALSE(r.blades[1].mu.has_value());
  EXPECT_EQ(r.blades[1].face_up, w.blades[1].face_up);
}

TEST(Snapshot, ContinuingFromASnapshotMatchesAnUninterruptedRun) {
  World a = FallingFibres();
  Simulation sim_a(a);
  sim_a.Prepare();
  sim_a.Run(2000);
  const std::string path = TempPath("fibrenet_continue.h5");
  io::WriteSnapshot(a, path);
  sim_a.Run(2000);

  World b = io::ReadSnapshot(path);
  Simulation sim_b(b);
  sim_b.Prepare();
  sim_b.Run(2000);
  ASSERT_GT(a.neighbours.ExportHistory().size(), 0u) << "the scene should have touching pairs";
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    ASSERT_EQ(a.particles.x[i], b.particles.x[i]) << "particle " << i;
    ASSERT_EQ(a.particles.omega[i], b.particles.omega[i]) << "particle " << i;
  }
}

// A network whose dashpots were never sized per bond stores no damping factors, and reads
// back without them (every factor 1), as a snapshot written before they existed does.
TEST(Snapshot, ANetworkWithoutDampingFactorsStoresNone) {
  const World w = FallingFibres();
  const std::string path = TempPath("fibrenet_without_factors.h5");
  io::WriteSnapshot(w, path);
  EXPECT_FALSE(io::Hdf5File(path, io::Hdf5File::Mode::kRead).Exists("bonds/damping_factors"));
  const World r = io::ReadSnapshot(path);
  ASSERT_EQ(r.bonds.size(), w.bonds.size());
  EXPECT_TRUE(r.bonds.damping_factors.empty());
  EXPECT_EQ(r.bonds.DampingFactors(2).translation, 1.0f);
}

TEST(Snapshot, MissingFileIsAnInputError) {
  EXPECT_THROW(io::ReadSnapshot(TempPath("does_not_exist.h5")), InputError);
}

}  // namespace
}  // namespace fibrenet
