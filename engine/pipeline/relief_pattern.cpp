#include "engine/pipeline/relief_pattern.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace fibrenet::pipeline {

namespace {

double Level(const ReliefPattern& p, double d) {
  const double inner = 0.5 * p.size - 0.5 * p.flank;
  if (d <= inner) return 1.0;
  if (d >= inner + p.flank) return 0.0;
  return 0.5 * (1.0 + std::cos(kPi * (d - inner) / p.flank));
}

// Whole number of periods in `length`, the nearest to length / pitch (at least one).
double FittedPitch(double length, double pitch) {
  return length / std::max(1.0, std::round(length / pitch));
}

}  // namespace

std::string ReliefPattern::Validate() const {
  if (!(pitch > 0.0 && pitch <= 0.1))
    return fmt::format("pitch = {} m: must lie in (0, 0.1]", pitch);
  if (!(size > 0.0 && size <= pitch))
    return fmt::format("size = {} m: must lie in (0, pitch = {}]", size, pitch);
  if (!(height > 0.0 && height <= 0.01))
    return fmt::format("height = {} m: must lie in (0, 0.01]", height);
  if (!(flank > 0.0 && flank <= size))
    return fmt::format("flank = {} m: must lie in (0, size = {}]", flank, size);
  return {};
}

std::shared_ptr<const Relief> MakeRelief(const ReliefPattern& pattern, const Cell& cell,
                                         double sign, double resolution) {
  auto relief = std::make_shared<Relief>();
  relief->x0 = cell.lo.x();
  relief->y0 = cell.lo.y();
  // Lines run along x: the pattern does not change along them, one period of one pitch.
  relief->period_x = pattern.shape == ReliefShape::kLines ? cell.Lx() : FittedPitch(cell.Lx(), pattern.pitch);
  relief->period_y = FittedPitch(cell.Ly(), pattern.pitch);
  const double step = std::min(resolution, 0.25 * pattern.flank);
  relief->nx = pattern.shape == ReliefShape::kLines
                   ? 2
                   : static_cast<std::size_t>(std::ceil(relief->period_x / step));
  relief->ny = static_cast<std::size_t>(std::ceil(relief->period_y / step));
  relief->height.resize(relief->nx * relief->ny);
  for (std::size_t j = 0; j < relief->ny; ++j)
    for (std::size_t i = 0; i < relief->nx; ++i) {
      // Feature centred in its period.
      const double dy = (static_cast<double>(j) / relief->ny - 0.5) * relief->period_y;
      const double dx = (static_cast<double>(i) / relief->nx - 0.5) * relief->period_x;
      const double d = pattern.shape == ReliefShape::kLines ? std::abs(dy) : std::hypot(dx, dy);
      relief->height[j * relief->nx + i] = sign * pattern.height * Level(pattern, d);
    }
  return relief;
}

double ReliefLevel(const Relief& relief, double x, double y) {
  const double scale = std::max(std::abs(relief.Max()), std::abs(relief.Min()));
  return scale > 0.0 ? std::abs(relief.At(x, y)) / scale : 0.0;
}

double Imprint(const World& w, const Relief& relief) {
  const Particles& p = w.particles;
  double flat = 0.0, patterned = 0.0;
  std::size_t n_flat = 0, n_patterned = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double level = ReliefLevel(relief, p.x[i].x(), p.x[i].y());
    if (level < 0.1) {
      flat += p.x[i].z();
      ++n_flat;
    } else if (level > 0.5) {
      patterned += p.x[i].z();
      ++n_patterned;
    }
  }
  if (n_flat == 0 || n_patterned == 0) return 0.0;
  return flat / static_cast<double>(n_flat) - patterned / static_cast<double>(n_patterned);
}

}  // namespace fibrenet::pipeline
