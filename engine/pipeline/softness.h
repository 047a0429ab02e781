// Softness of a sheet (SPEC 2.5): bulk softness, surface roughness, bending stiffness, and a
// composite softness index. What each stands for against the instruments tissue makers use
// is in docs/virtual-tests.md; in short:
//
//  bulk_softness_um_per_kPa  thickness lost per kPa of pressure on the loading branch of the
//                            ZD compression in its low-pressure window (compression_test.h):
//                            h0 / zd_modulus. Large = bulky, compliant, "soft in the hand"
//                            (KES-FB3 LC/WC, caliper under a light foot).
//  surface_roughness_um      RMS deviation (Sq) of the top surface height from its mean. The
//                            surface is what a ball probe of radius probe_radius resting on the
//                            sheet from above touches (the morphological closing of the
//                            spheres' tops), sampled on a square grid of pitch grid_pitch; where
//                            the probe falls through a hole it reads the sheet's bottom. The
//                            probe is at least one grid pitch in radius: a finer one would
//                            alias holes narrower than the pitch into the map.
//                            Its spectrum: the mean over grid rows (x) and columns (y) of the
//                            squared DFT amplitudes of the profile, per wavelength; the largest
//                            gives surface_dominant_wavelength_um. (KES-FB4 SMD; Emtec TSA TS750.)
//  bending_stiffness         sheet bending stiffness per unit width D [mN mm = uN m]. Method
//                            kPureBending (default) bends a strip at a constant curvature
//                            between two grips that turn about the strip's mid-plane, as the
//                            KES-FB2 pure bending tester does, and fits moment/width vs
//                            curvature (sheet_bending.h). Method kPlate takes the plate formula
//                            D = S t^2 / 12 from the tensile stiffness S (geometric mean of MD
//                            and CD moduli) and the thickness t: an upper bound that assumes
//                            the sheet bends as a solid plate (every layer bonded to the next),
//                            cheap but blind to the low interlayer bonding of tissue.
//                            (Emtec TSA D, Handle-O-Meter, KES-FB2 B.)
//  softness_index            100 * (B / B_ref)^w_B * (Sq_ref / Sq)^w_R * (D_ref / D)^w_D:
//                            100 for the reference sheet; rises with bulk softness, falls with
//                            roughness and bending stiffness. A doubling of B adds w_B * 100%
//                            (log-additive, like the TSA handfeel regression HF on TS7, TS750
//                            and D). Weights default to 0.4, 0.2, 0.4 and references to the
//                            generic tissue of docs/virtual-tests.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/pipeline/compression_test.h"
#include "engine/pipeline/curves.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"
#include "engine/pipeline/sheet_bending.h"
#include "engine/pipeline/tensile_test.h"

namespace fibrenet::pipeline {

enum class BendingMethod { kPureBending, kPlate };

struct SoftnessIndexSettings {
  double w_bulk = 0.4, w_roughness = 0.2, w_bending = 0.4;  // each in [0, 5]
  double bulk_ref_um_per_kPa = 20.0;   // B_ref
  double roughness_ref_um = 30.0;      // Sq_ref
  double bending_ref_mN_mm = 0.5;      // D_ref

  std::string Validate() const;
};

struct SoftnessSettings {
  double grid_pitch = 10e-6;     // height map pitch [m], (0, 1e-3]
  double probe_radius = 100e-6;  // [m], [0, 1e-2]
  BendingMethod bending = BendingMethod::kPureBending;
  BendingSettings bending_test;       // kPureBending
  // Bulk softness when no ZD result is given: a light compression, to 4 kPa (or strain 0.6).
  CompressionSettings compression = [] {
    CompressionSettings c;
    c.max_pressure = 4000.0;
    return c;
  }();
  TensileSettings tensile;            // kPlate, when no tensile result is given
  SoftnessIndexSettings index;

  std::string Validate() const;
};

// Results of the other tests that softness can reuse instead of running them again.
struct SoftnessInputs {
  const CompressionResult* compression = nullptr;
  const TensileResult* md = nullptr;
  const TensileResult* cd = nullptr;
};

struct SoftnessResult {
  std::vector<Metric> metrics;
  // "roughness_spectrum_md"/"_cd": wavelength_um, amplitude_um (RMS amplitude of that
  // harmonic); "height_profile": x_um, height_um along the grid row at mid y;
  // plus the bending curve (kPureBending) and any compression run here.
  std::vector<Curve> curves;
  std::vector<std::string> warnings;
  std::int64_t steps = 0;  // of the tests it ran itself (compression, bending, tensile)

  double Value(const std::string& name) const;
};

SoftnessResult RunSoftnessTest(const Network& net, const SoftnessSettings& s,
                               const SoftnessInputs& inputs = {}, const Progress& progress = {});

// Height of the top surface seen by a ball probe of radius max(probe_radius, pitch) (the
// lateral resolution of the map), on an nx x ny grid
// over the periodic cell (pitches Lx/nx, Ly/ny nearest the asked pitch), row-major (index
// iy * nx + ix) [m].
struct HeightMap {
  int nx = 0, ny = 0;
  double pitch_x = 0.0, pitch_y = 0.0;
  std::vector<double> z;
};
HeightMap TopSurface(const World& w, double pitch, double probe_radius);

// Sq of a height map and the spectra of its profiles along x (MD: the grid rows) and along y
// (CD: the columns): wavelength [m] and RMS amplitude [m] of each harmonic, averaged over the
// profiles; per direction the squared amplitudes sum to the profiles' mean variance.
struct Spectrum {
  std::vector<double> wavelength, amplitude;
};
struct Roughness {
  double sq = 0.0;
  Spectrum md, cd;
  double dominant_wavelength = 0.0;  // of the largest amplitude in either direction [m]
};
Roughness MeasureRoughness(const HeightMap& map);

double SoftnessIndex(double bulk_um_per_kPa, double roughness_um, double bending_mN_mm,
                     const SoftnessIndexSettings& s);

}  // namespace fibrenet::pipeline
