#include "engine/io/snapshot.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <utility>

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/io/hdf5_file.h"
#include "engine/io/xdmf.h"

namespace fibrenet::io {

namespace {

constexpr double kFormatVersion = 1.0;
constexpr std::size_t kTypeColumns = 18;

std::vector<double> Flatten(const std::vector<Vec3>& v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const Vec3& a : v) out.insert(out.end(), {a.x(), a.y(), a.z()});
  return out;
}

std::vector<Vec3> Unflatten3(const std::vector<double>& d) {
  std::vector<Vec3> out(d.size() / 3);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = Vec3(d[3 * k], d[3 * k + 1], d[3 * k + 2]);
  return out;
}

// A blade's row of blades/state: tip, face normal, face up, velocity (x y z each), friction
// (0 or 1), mu (-1: the contacts'), hard stiffness, hard gap, work, reaction (x y z).
constexpr std::size_t kBladeColumns = 20;

void AppendBladeRow(const Blade& b, std::vector<double>& out) {
  for (const Vec3& v : {b.tip, b.face_normal, b.face_up, b.velocity})
    out.insert(out.end(), {v.x(), v.y(), v.z()});
  out.insert(out.end(), {b.friction ? 1.0 : 0.0, b.mu.value_or(-1.0), b.hard_stiffness, b.hard_gap,
                         b.work, b.reaction.x(), b.reaction.y(), b.reaction.z()});
}

Blade BladeOfRow(const double* s) {
  Blade b;
  b.tip = Vec3(s[0], s[1], s[2]);
  b.face_normal = Vec3(s[3], s[4], s[5]);
  b.face_up = Vec3(s[6], s[7], s[8]);
  b.velocity = Vec3(s[9], s[10], s[11]);
  b.friction = s[12] != 0.0;
  if (s[13] >= 0.0) b.mu = s[13];
  b.hard_stiffness = s[14];
  b.hard_gap = s[15];
  b.work = s[16];
  b.reaction = Vec3(s[17], s[18], s[19]);
  return b;
}

std::vector<double> FlattenQuats(const std::vector<Quat>& v) {
  std::vector<double> out;
  out.reserve(4 * v.size());
  for (const Quat& q : v) out.insert(out.end(), {q.w(), q.x(), q.y(), q.z()});
  return out;
}

std::vector<Quat> UnflattenQuats(const std::vector<double>& d) {
  std::vector<Quat> out(d.size() / 4);
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = Quat(d[4 * k], d[4 * k + 1], d[4 * k + 2], d[4 * k + 3]);
  return out;
}

template <typename T>
std::vector<std::int64_t> ToInts(const std::vector<T>& v) {
  return std::vector<std::int64_t>(v.begin(), v.end());
}

// rows x cols values, row k filled by fill(k, pointer to its first value).
template <typename T, typename Fill>
std::vector<T> BondRows(std::size_t rows, std::size_t cols, Fill fill) {
  std::vector<T> out(rows * cols);
  for (std::size_t k = 0; k < rows; ++k) fill(k, out.data() + k * cols);
  return out;
}

std::vector<double> TypeRow(const BeamBondParams& p) {
  return {p.k_n,         p.k_s,         p.k_b,       p.k_t,       static_cast<double>(p.failure),
          p.max_tension, p.max_shear,   p.max_bending, p.max_twist, p.F_r0,
          p.F_s0,        p.G_b0,        p.G_t0,      p.maxwell_tau, p.yield_moment,
          p.damping_n,   p.damping_s,   p.damping_rot};
}

BeamBondParams TypeFromRow(const double* r) {
  BeamBondParams p;
  p.k_n = r[0]; p.k_s = r[1]; p.k_b = r[2]; p.k_t = r[3];
  p.failure = static_cast<BondFailure>(static_cast<int>(r[4]));
  p.max_tension = r[5]; p.max_shear = r[6]; p.max_bending = r[7]; p.max_twist = r[8];
  p.F_r0 = r[9]; p.F_s0 = r[10]; p.G_b0 = r[11]; p.G_t0 = r[12];
  p.maxwell_tau = r[13]; p.yield_moment = r[14];
  p.damping_n = r[15]; p.damping_s = r[16]; p.damping_rot = r[17];
  return p;
}

void WriteScalars(Hdf5File& f, const World& w) {
  f.WriteAttribute("format_version", kFormatVersion);
  f.WriteAttribute("time", w.time);
  f.WriteAttribute("step", static_cast<double>(w.step));
  f.WriteAttribute("min_contact_ratio", w.min_contact_ratio);
  const Vec3 lo = w.cell.lo, hi = w.cell.hi;
  for (int a = 0; a < 3; ++a) {
    f.WriteAttribute(fmt::format("cell_lo_{}", a), lo[a]);
    f.WriteAttribute(fmt::format("cell_hi_{}", a), hi[a]);
  }
  f.WriteAttribute("cell_periodic_x", w.cell.periodic_x);
  f.WriteAttribute("cell_periodic_y", w.cell.periodic_y);
  const Physics& ph = w.physics;
  f.WriteAttribute("gravity", ph.gravity);
  for (int a = 0; a < 3; ++a) f.WriteAttribute(fmt::format("g_{}", a), ph.g[a]);
  f.WriteAttribute("drag", ph.drag);
  f.WriteAttribute("drag_coefficient", ph.drag_coefficient);
  for (int a = 0; a < 3; ++a) f.WriteAttribute(fmt::format("air_velocity_{}", a), ph.air_velocity[a]);
  f.WriteAttribute("contacts", ph.contacts);
  f.WriteAttribute("friction", ph.friction);
  f.WriteAttribute("applied_loads", ph.applied_loads);
  const ContactParams& c = w.contact;
  f.WriteAttribute("contact_C", c.normal.C);
  f.WriteAttribute("contact_g", c.normal.g);
  f.WriteAttribute("contact_linear_below", c.normal.linear_below);
  f.WriteAttribute("contact_restitution", c.restitution);
  f.WriteAttribute("contact_mu", c.mu);
  f.WriteAttribute("contact_tangential_ratio", c.tangential_ratio);
  const StepSettings& s = w.settings;
  f.WriteAttribute("dt", s.dt);
  f.WriteAttribute("safety", s.safety);
  f.WriteAttribute("policy", static_cast<double>(s.policy));
  f.WriteAttribute("skin", s.skin);
  f.WriteAttribute("contacts_per_particle_bound", s.contacts_per_particle_bound);
  f.WriteAttribute("max_step_displacement", s.max_step_displacement);
  const EnergyLedger& e = w.energy;
  f.WriteAttribute("energy_damping", e.damping);
  f.WriteAttribute("energy_friction", e.friction);
  f.WriteAttribute("energy_bond_inelastic", e.bond_inelastic);
  f.WriteAttribute("energy_released", e.released);
  f.WriteAttribute("energy_overlap_regained", e.overlap_regained);
  f.WriteAttribute("work_gravity", e.work_gravity);
  f.WriteAttribute("work_drag", e.work_drag);
  f.WriteAttribute("work_walls", e.work_walls);
  f.WriteAttribute("work_applied", e.work_applied);
}

void ReadScalars(const Hdf5File& f, World& w) {
  if (f.ReadAttribute("format_version") != kFormatVersion)
    throw Error(fmt::format("{}: snapshot format version {} is not supported (expected {})",
                            f.path(), f.ReadAttribute("format_version"), kFormatVersion));
  w.time = f.ReadAttribute("time");
  w.step = static_cast<std::int64_t>(f.ReadAttribute("step"));
  w.min_contact_ratio = f.ReadAttribute("min_contact_ratio");
  for (int a = 0; a < 3; ++a) {
    w.cell.lo[a] = f.ReadAttribute(fmt::format("cell_lo_{}", a));
    w.cell.hi[a] = f.ReadAttribute(fmt::format("cell_hi_{}", a));
  }
  w.cell.periodic_x = f.ReadAttribute("cell_periodic_x") != 0.0;
  w.cell.periodic_y = f.ReadAttribute("cell_periodic_y") != 0.0;
  Physics& ph = w.physics;
  ph.gravity = f.ReadAttribute("gravity") != 0.0;
  for (int a = 0; a < 3; ++a) ph.g[a] = f.ReadAttribute(fmt::format("g_{}", a));
  ph.drag = f.ReadAttribute("drag") != 0.0;
  ph.drag_coefficient = f.ReadAttribute("drag_coefficient");
  for (int a = 0; a < 3; ++a)
    ph.air_velocity[a] = f.ReadAttribute(fmt::format("air_velocity_{}", a));
  ph.contacts = f.ReadAttribute("contacts") != 0.0;
  ph.friction = f.ReadAttribute("friction") != 0.0;
  ph.applied_loads = f.ReadAttribute("applied_loads") != 0.0;
  ContactParams& c = w.contact;
  c.normal.C = f.ReadAttribute("contact_C");
  c.normal.g = f.ReadAttribute("contact_g");
  c.normal.linear_below = f.ReadAttribute("contact_linear_below");
  c.restitution = f.ReadAttribute("contact_restitution");
  c.mu = f.ReadAttribute("contact_mu");
  c.tangential_ratio = f.ReadAttribute("contact_tangential_ratio");
  c.Derive();
  StepSettings& s = w.settings;
  s.dt = f.ReadAttribute("dt");
  s.safety = f.ReadAttribute("safety");
  s.policy = static_cast<TimeStepPolicy>(static_cast<int>(f.ReadAttribute("policy")));
  s.skin = f.ReadAttribute("skin");
  s.contacts_per_particle_bound = static_cast<int>(f.ReadAttribute("contacts_per_particle_bound"));
  s.max_step_displacement = f.ReadAttribute("max_step_displacement");
  EnergyLedger& e = w.energy;
  e.damping = f.ReadAttribute("energy_damping");
  e.friction = f.ReadAttribute("energy_friction");
  e.bond_inelastic = f.ReadAttribute("energy_bond_inelastic");
  e.released = f.ReadAttribute("energy_released");
  // Snapshots written before the ledger had the term carry none.
  e.overlap_regained =
      f.HasAttribute("energy_overlap_regained") ? f.ReadAttribute("energy_overlap_regained") : 0.0;
  e.work_gravity = f.ReadAttribute("work_gravity");
  e.work_drag = f.ReadAttribute("work_drag");
  e.work_walls = f.ReadAttribute("work_walls");
  e.work_applied = f.ReadAttribute("work_applied");
}

}  // namespace

void WriteSnapshot(const World& w, const std::string& path, const PointFields& fields,
                   const ExtraWriter& extra) {
  const Particles& p = w.particles;
  for (const auto& [name, values] : fields)
    if (values.size() != p.size())
      throw Error(fmt::format("{}: field {} has {} values for {} particles", path, name,
                              values.size(), p.size()));
  // Write to a temporary name and rename, so a crash never leaves half a snapshot.
  // The process id keeps processes that write the same snapshot (MPI ranks sharing a stage
  // cache folder) out of each other's partial file.
  const std::string partial = fmt::format("{}.partial.{}", path, ::getpid());
  {
    Hdf5File f(partial, Hdf5File::Mode::kCreate);
    WriteScalars(f, w);
    f.CreateGroup("particles");
    f.WriteDoubles("particles/x", Flatten(p.x), 3);
    f.WriteDoubles("particles/v", Flatten(p.v), 3);
    f.WriteDoubles("particles/omega", Flatten(p.omega), 3);
    f.WriteDoubles("particles/q", FlattenQuats(p.q), 4);
    f.WriteDoubles("particles/radius", p.radius, 1);
    f.WriteDoubles("particles/mass", p.mass, 1);
    f.WriteDoubles("particles/inertia", p.inertia, 1);
    f.WriteDoubles("particles/inv_mass", p.inv_mass, 1);
    f.WriteDoubles("particles/inv_inertia", p.inv_inertia, 1);
    f.WriteInts("particles/fibre", ToInts(p.fibre), 1);

    const Bonds& b = w.bonds;
    f.CreateGroup("bonds");
    // Each column is built, written and freed in turn: a snapshot of a large network holds
    // one column of its bonds in memory at a time.
    const std::size_t nb = b.size();
    f.WriteInts("bonds/ij", BondRows<std::int64_t>(nb, 2, [&](std::size_t k, auto out) {
                  out[0] = b.i[k];
                  out[1] = b.j[k];
                }), 2);
    f.WriteInts("bonds/type", ToInts(b.type), 1);
    f.WriteInts("bonds/kind", BondRows<std::int64_t>(nb, 1, [&](std::size_t k, auto out) {
                  out[0] = static_cast<std::int64_t>(b.kind[k]);
                }), 1);
    f.WriteInts("bonds/broken", ToInts(b.broken), 1);
    f.WriteDoubles("bonds/L0", BondRows<double>(nb, 1, [&](std::size_t k, auto out) {
                     out[0] = b.state[k].L0;
                   }), 1);
    // The bond's frame in each particle's body frame, as w, x, y, z.
    for (const auto& column : {std::pair{"bonds/b_i", &BondState::b_i},
                               std::pair{"bonds/b_j", &BondState::b_j}}) {
      const auto frame = column.second;
      f.WriteDoubles(column.first, BondRows<double>(nb, 4, [&](std::size_t k, auto out) {
                       const Quat& q = b.state[k].*frame;
                       out[0] = q.w();
                       out[1] = q.x();
                       out[2] = q.y();
                       out[3] = q.z();
                     }), 4);
    }
    f.WriteDoubles("bonds/dashpot", BondRows<double>(nb, 1, [&](std::size_t k, auto out) {
                     out[0] = b.state[k].dashpot;
                   }), 1);
    f.WriteDoubles("bonds/plastic", BondRows<double>(nb, 2, [&](std::size_t k, auto out) {
                     out[0] = b.state[k].plastic_y;
                     out[1] = b.state[k].plastic_z;
                   }), 2);
    if (!b.damping_factors.empty())
      f.WriteDoubles("bonds/damping_factors", BondRows<double>(nb, 2, [&](std::size_t k, auto out) {
                       out[0] = b.damping_factors[k].translation;
                       out[1] = b.damping_factors[k].rotation;
                     }), 2);
    std::vector<double> types;
    for (const BeamBondParams& t : b.types) {
      const std::vector<double> row = TypeRow(t);
      types.insert(types.end(), row.begin(), row.end());
    }
    f.WriteDoubles("bonds/types", types, kTypeColumns);
    std::vector<double> events;  // step, bond, x, y, z, f_r, f_s, tau_b, tau_t, energy
    for (const BondBreakEvent& e : b.events)
      events.insert(events.end(), {static_cast<double>(e.step), static_cast<double>(e.bond),
                                   e.position.x(), e.position.y(), e.position.z(), e.f_r, e.f_s,
                                   e.tau_b, e.tau_t, e.energy});
    f.WriteDoubles("bonds/events", events, 10);

    f.CreateGroup("contacts");
    std::vector<std::int64_t> pairs;
    std::vector<double> xi;
    for (const PairHistory& h : w.neighbours.ExportHistory()) {
      pairs.insert(pairs.end(), {h.i, h.j});
      xi.insert(xi.end(), {h.xi.x(), h.xi.y(), h.xi.z()});
    }
    f.WriteInts("contacts/ij", pairs, 2);
    f.WriteDoubles("contacts/xi", xi, 3);

    f.CreateGroup("walls");
    std::vector<double> walls;  // z, vz, side, friction, work, reaction x y z
    for (const Wall& wall : w.walls)
      walls.insert(walls.end(), {wall.z, wall.vz, static_cast<double>(wall.side),
                                 wall.friction ? 1.0 : 0.0, wall.work, wall.reaction.x(),
                                 wall.reaction.y(), wall.reaction.z()});
    f.WriteDoubles("walls/state", walls, 8);
    for (std::size_t k = 0; k < w.walls.size(); ++k)
      f.WriteDoubles(fmt::format("walls/history_{}", k), Flatten(w.walls[k].history), 3);

    // The blades (creping's impact frames): where each is, how it moves and its contacts.
    f.CreateGroup("blades");
    std::vector<double> blades;
    for (const Blade& blade : w.blades) AppendBladeRow(blade, blades);
    f.WriteDoubles("blades/state", blades, kBladeColumns);
    for (std::size_t k = 0; k < w.blades.size(); ++k)
      f.WriteDoubles(fmt::format("blades/history_{}", k), Flatten(w.blades[k].history), 3);

    if (w.physics.applied_loads) {
      f.WriteDoubles("particles/applied_force", Flatten(w.applied_force), 3);
      f.WriteDoubles("particles/applied_torque", Flatten(w.applied_torque), 3);
    }
    f.CreateGroup("fields");
    for (const auto& [name, values] : fields) f.WriteDoubles("fields/" + name, values, 1);
    f.CreateGroup("xdmf");
    std::vector<std::int64_t> intact;  // the bonds ParaView draws
    intact.reserve(2 * b.CountIntact());
    for (std::size_t k = 0; k < nb; ++k)
      if (!b.broken[k]) intact.insert(intact.end(), {b.i[k], b.j[k]});
    f.WriteInts("xdmf/bonds", intact, 2);
    if (extra) extra(f);
    f.Save();
  }
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);
  if (ec) throw Error(fmt::format("{}: cannot move snapshot into place: {}", path, ec.message()));
  std::vector<std::string> names;
  for (const auto& entry : fields) names.push_back(entry.first);
  WriteXdmf(path, p.size(), w.bonds.CountIntact(), names, w.time);
}

World ReadSnapshot(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(fmt::format("{}: snapshot file not found", path));
  Hdf5File f(path, Hdf5File::Mode::kRead);
  World w;
  ReadScalars(f, w);
  Particles& p = w.particles;
  p.x = Unflatten3(f.ReadDoubles("particles/x", 3));
  const std::size_t n = p.x.size();
  p.v = Unflatten3(f.ReadDoubles("particles/v", 3));
  p.omega = Unflatten3(f.ReadDoubles("particles/omega", 3));
  p.q = UnflattenQuats(f.ReadDoubles("particles/q", 4));
  p.radius = f.ReadDoubles("particles/radius", 1);
  p.mass = f.ReadDoubles("particles/mass", 1);
  p.inertia = f.ReadDoubles("particles/inertia", 1);
  p.inv_mass = f.ReadDoubles("particles/inv_mass", 1);
  p.inv_inertia = f.ReadDoubles("particles/inv_inertia", 1);
  const auto fibre = f.ReadInts("particles/fibre", 1);
  p.fibre.assign(fibre.begin(), fibre.end());
  p.force.assign(n, Vec3::Zero());
  p.torque.assign(n, Vec3::Zero());
  if (p.v.size() != n || p.omega.size() != n || p.q.size() != n || p.radius.size() != n ||
      p.mass.size() != n || p.inertia.size() != n || p.inv_mass.size() != n ||
      p.inv_inertia.size() != n || p.fibre.size() != n)
    throw Error(fmt::format("{}: particle arrays have inconsistent lengths", path));

  Bonds& b = w.bonds;
  const auto types = f.ReadDoubles("bonds/types", kTypeColumns);
  for (std::size_t t = 0; t < types.size() / kTypeColumns; ++t)
    b.types.push_back(TypeFromRow(types.data() + t * kTypeColumns));
  const auto ij = f.ReadInts("bonds/ij", 2);
  const auto type = f.ReadInts("bonds/type", 1);
  const auto kind = f.ReadInts("bonds/kind", 1);
  const auto broken = f.ReadInts("bonds/broken", 1);
  const auto L0 = f.ReadDoubles("bonds/L0", 1);
  const auto b_i = UnflattenQuats(f.ReadDoubles("bonds/b_i", 4));
  const auto b_j = UnflattenQuats(f.ReadDoubles("bonds/b_j", 4));
  const auto dashpot = f.ReadDoubles("bonds/dashpot", 1);
  const auto plastic = f.ReadDoubles("bonds/plastic", 2);
  // Only a network whose dashpots were sized per bond holds damping factors.
  const std::vector<double> damping = f.Exists("bonds/damping_factors")
                                          ? f.ReadDoubles("bonds/damping_factors", 2)
                                          : std::vector<double>{};
  const std::size_t nb = L0.size();
  if (ij.size() != 2 * nb || type.size() != nb || kind.size() != nb || broken.size() != nb ||
      b_i.size() != nb || b_j.size() != nb || dashpot.size() != nb || plastic.size() != 2 * nb ||
      (!damping.empty() && damping.size() != 2 * nb))
    throw Error(fmt::format("{}: bond arrays have inconsistent lengths", path));
  for (std::size_t k = 0; k < nb; ++k) {
    BondState s;
    s.L0 = L0[k];
    s.b_i = b_i[k];
    s.b_j = b_j[k];
    s.dashpot = dashpot[k];
    s.plastic_y = plastic[2 * k];
    s.plastic_z = plastic[2 * k + 1];
    if (ij[2 * k] < 0 || ij[2 * k] >= static_cast<std::int64_t>(n) || ij[2 * k + 1] < 0 ||
        ij[2 * k + 1] >= static_cast<std::int64_t>(n) || type[k] < 0 ||
        type[k] >= static_cast<std::int64_t>(b.types.size()))
      throw Error(fmt::format("{}: bond {} refers to a missing particle or type", path, k));
    b.Add(static_cast<std::int32_t>(ij[2 * k]), static_cast<std::int32_t>(ij[2 * k + 1]),
          static_cast<std::int32_t>(type[k]), static_cast<BondKind>(kind[k]), s);
    b.broken.back() = static_cast<std::uint8_t>(broken[k]);
  }
  for (std::size_t k = 0; k < damping.size() / 2; ++k)
    b.damping_factors.push_back(
        {static_cast<float>(damping[2 * k]), static_cast<float>(damping[2 * k + 1])});
  const auto events = f.ReadDoubles("bonds/events", 10);
  for (std::size_t k = 0; k < events.size() / 10; ++k) {
    const double* e = events.data() + 10 * k;
    BondBreakEvent ev;
    ev.step = static_cast<std::int64_t>(e[0]);
    ev.bond = static_cast<std::int32_t>(e[1]);
    ev.position = Vec3(e[2], e[3], e[4]);
    ev.f_r = e[5]; ev.f_s = e[6]; ev.tau_b = e[7]; ev.tau_t = e[8]; ev.energy = e[9];
    b.events.push_back(ev);
  }

  const auto walls = f.ReadDoubles("walls/state", 8);
  for (std::size_t k = 0; k < walls.size() / 8; ++k) {
    const double* s = walls.data() + 8 * k;
    Wall wall;
    wall.z = s[0]; wall.vz = s[1]; wall.side = static_cast<int>(s[2]);
    wall.friction = s[3] != 0.0; wall.work = s[4]; wall.reaction = Vec3(s[5], s[6], s[7]);
    wall.history = Unflatten3(f.ReadDoubles(fmt::format("walls/history_{}", k), 3));
    w.walls.push_back(std::move(wall));
  }
  if (f.Exists("blades/state")) {  // snapshots before 2026-12-07 kept no blades
    const auto blades = f.ReadDoubles("blades/state", kBladeColumns);
    for (std::size_t k = 0; k < blades.size() / kBladeColumns; ++k) {
      Blade blade = BladeOfRow(blades.data() + kBladeColumns * k);
      blade.history = Unflatten3(f.ReadDoubles(fmt::format("blades/history_{}", k), 3));
      w.blades.push_back(std::move(blade));
    }
  }
  if (w.physics.applied_loads) {
    w.applied_force = Unflatten3(f.ReadDoubles("particles/applied_force", 3));
    w.applied_torque = Unflatten3(f.ReadDoubles("particles/applied_torque", 3));
  }
  if (w.physics.contacts) {
    w.neighbours.Build(p, w.cell, w.bonds, w.settings.skin);
    const auto pairs = f.ReadInts("contacts/ij", 2);
    const auto xi = Unflatten3(f.ReadDoubles("contacts/xi", 3));
    std::vector<PairHistory> history;
    for (std::size_t k = 0; k < xi.size(); ++k)
      history.push_back({static_cast<std::int32_t>(pairs[2 * k]),
                         static_cast<std::int32_t>(pairs[2 * k + 1]), xi[k]});
    w.neighbours.ImportHistory(history);
  }
  return w;
}

}  // namespace fibrenet::io
