// Built-in problems: a generator (mesh, materials, initial cells) and its
// checks, registered by name (CONTRIBUTING.md style 1: the driver only looks them up).
#pragma once

#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "data/mesh.hpp"
#include "data/state.hpp"
#include "input/config.hpp"
#include "mesh_setup.hpp"
#include "parallel.hpp"
#include "state_setup.hpp"
#include "step_report.hpp"

namespace lagremap {

// A validation number of a problem: passes when |value - reference| <= tolerance.
// The optional numbers put a remap result next to what it is compared with in
// the source paper's figures (summary.json writes them only when set).
struct Check {
  Check() = default;
  // The required fields (a constructor so that brace lists of five stay
  // complete initialisations, without -Wmissing-field-initializers).
  Check(std::string name, double value, double reference, double tolerance, std::string note)
      : name(std::move(name)),
        value(value),
        reference(reference),
        tolerance(tolerance),
        note(std::move(note)) {}
  std::string name;
  double value = 0.0, reference = 0.0, tolerance = 0.0;
  std::string note;  // what the number is and where the reference comes from
  // Remap mode: the reference the same check has in lagrange mode.
  std::optional<double> lagrange_reference;
  // The paper's number for this quantity in this run's mode (docs/verification.md §8).
  std::optional<double> paper;
  // Where the reference comes from ("exact two-wave solution", "Howell-Ball",
  // "paper, default parameters only", ...).
  std::string source;
  // A reference that holds for one case only (the paper's parameters, or the
  // state at the case's t_end) does not apply to another run: reported with
  // the reason, never a failure, never in the exit code.
  bool applies = true;
  std::string not_applicable;  // why not (which parameter differs, ...)
  bool pass() const;           // |value - reference| <= tolerance
  bool counts() const { return applies; }
  // Marks the check as not applying, with the reason.
  void doesNotApply(std::string reason) {
    applies = false;
    not_applicable = std::move(reason);
  }
};

// Why the run is not the built-in case a paper-only reference describes:
// the first physics key (material, geometry, speed, gas, boundary conditions,
// t_end) whose value differs from the problem's default, as "key = value
// (case: default)"; "" for the case itself. Resolution (mesh.*, --scale),
// numerics.*, remap.* and check.* keys do not change the case.
std::string differenceFromDefaultCase(const Config& config);
// Marks each check in `names` (all when empty) as not applying where the
// material <prefix> hardens (<prefix>.hardening is not perfect): their
// references are solutions for perfect plasticity.
void markPerfectPlasticityOnly(const Config& config, std::vector<Check>& checks,
                               const std::string& prefix,
                               const std::vector<std::string>& names = {});
// Marks each check in `names` as not applying where the run is not the
// default case (differenceFromDefaultCase), and sets their source.
void markDefaultCaseOnly(const Config& config, std::vector<Check>& checks,
                         const std::vector<std::string>& names, const std::string& source);

// L1 norms of the errors of the final state against a problem's exact
// solution (summary.json "l1_errors"): density, velocity (|V - V_exact|, the
// vector's magnitude; the x-component's difference on a bar) and pressure,
// each an integral of |q - q_exact| dV over the cells the note names, with
// exact sums over the owned cells and the ranks (ExactSum: the same bits on
// any rank count), and the note saying what is integrated and divided by what.
struct L1Errors {
  double density = 0.0, velocity = 0.0, pressure = 0.0;
  std::string note;
};

// The note of a bar's L1 errors against an exact solution sampled at each
// cell's centroid (the shock tubes).
inline constexpr const char* kBarL1ErrorsNote =
    "integral over the bar of |q - q_exact| dV divided by its cross-section area (kg/m^2, m^2/s, "
    "Pa m); velocity: the x-component; q_exact: the exact solution at each cell's centroid";

// What a problem's finish returns: its checks and, where the run has an exact
// solution, the L1 errors against it (none where the solution does not
// apply to the run's parameters).
struct ProblemResults {
  ProblemResults() = default;
  // (implicit: a problem without an exact solution returns its checks alone)
  ProblemResults(std::vector<Check> checks) : checks(std::move(checks)) {}
  std::vector<Check> checks;
  std::optional<L1Errors> l1_errors;
};

// Initial cell state, host side, one entry per cell: a pure cell of material
// `mat` at (rho, e), unless the mixed-cell arrays are given.
struct InitialCells {
  std::vector<double> rho, e;  // density, specific internal energy
  std::vector<Vec3> v;         // velocity
  std::vector<int> mat;        // material index into ProblemSetup::materials
  // Optional mixed cells, n_cells x n_materials (cell-major): volume fraction,
  // material density and specific internal energy; when given they replace
  // rho, e and mat (docs/method.md §A3: m^k = alpha^k rho^k v).
  std::vector<double> alpha_k, rho_k, e_k;
};

struct ProblemSetup {
  Mesh mesh;
  std::vector<MaterialParams> materials;
  InitialCells cells;
  // Wall time fillMaterialRegions took (the set-up's "sample materials"
  // phase, summary.json); the rest of Problem::setup is "generate".
  double sample_seconds = 0.0;
};

// Host copies of the fields at the end of a run, for problem checks and CSVs:
// on one rank the block's cells in global order; on a decomposed run this
// rank's held cells (`distributed`): `owned` marks the ones it owns,
// `cell_global` gives their global ids, and `mesh` is the rank's own (local
// node ids). Every problem's `finish` reads owned cells and combines over the
// ranks: no rank holds a field of the whole block (tests may ask for the
// whole block's on every rank, RunOptions::gather_final_fields).
struct FinalFields {
  double time = 0.0;
  int nx = 0, ny = 0, nz = 0;
  bool distributed = false;
  Kokkos::View<int*, HostSpace> owned;         // (distributed only)
  Kokkos::View<long*, HostSpace> cell_global;  // (distributed only)
  // Whether cell c is this rank's to count (every cell of whole fields).
  bool counts(Index c) const { return !distributed || owned(c); }
  long globalCell(Index c) const { return distributed ? cell_global(c) : long(c); }
  HostMesh mesh;
  RealView::HostMirror rho, p, e, vol;
  Vec3View::HostMirror v, x_c;
  Sym6View::HostMirror S;                 // deviatoric stress (mixture)
  MatRealView::HostMirror alpha;          // volume fraction of each material
  MatRealView::HostMirror m_k, e_k, p_k;  // mass, specific internal energy, pressure per material
  MatRealView::HostMirror eps_k;  // plastic strain per material (empty: no hypo-elastic solid)
  // Each material's normal stress across its interface, tension positive, as
  // the closure balances it (interfaceNormalStress; multi-material runs only).
  MatRealView::HostMirror sigma_n_k;
  // The plastic strain of cell c: its materials' eps_p^k by mass (a fluid's
  // is 0; a light gas beside a metal barely dilutes the metal's).
  double plasticStrain(Index c) const {
    double strained = 0.0, mass = 0.0;
    for (Index k = 0; k < Index(eps_k.extent(1)); ++k) {
      if (!(alpha(c, k) > 0.0)) continue;
      strained += m_k(c, k) * eps_k(c, k);
      mass += m_k(c, k);
    }
    return mass > 0.0 ? strained / mass : 0.0;
  }
  // The problem's probe after every step: (t, value), first entry at t = 0.
  std::vector<std::pair<double, double>> probe;
};

// A number a problem measures after every step. `sample` launches its
// reductions into the step report's slots without waiting (the step's one
// host synchronisation, docs/performance.md §8, reads them); after the fence
// `value` makes the number of them (collective: it reduces over the ranks; a
// probe of several dependent passes launches and waits for the later ones here).
// `name`: probe.csv's column.
struct Probe {
  void (*sample)(const Mesh& mesh, const State& state, const ProbeSlots& slots) = nullptr;
  double (*value)(const Mesh& mesh, const State& state, const ProbeSlots& slots) = nullptr;
  const char* name = nullptr;

  explicit operator bool() const { return sample != nullptr; }
  // Sampled and waited for (the set-up's first entry).
  double measure(const Mesh& mesh, const State& state) const;
};

struct Problem {
  const char* name;
  const char* description;
  // Declares every problem key with its default (materials, geometry, boundary
  // conditions, mesh, t_end).
  void (*declare)(Config& config);
  ProblemSetup (*setup)(const Config& config);
  // Writes the problem's CSVs into out_dir and returns its checks (and its
  // L1 errors where it has an exact solution).
  ProblemResults (*finish)(const Config& config, const FinalFields& fields,
                           const std::string& out_dir);
  // Optional: a number measured after every step (e.g. a wall stress), kept
  // in FinalFields::probe and written to probe.csv (Probe).
  Probe probe = {};
  // Snapshot times when the command line gives none (docs/verification.md §8), those up to t_end.
  std::vector<double> default_output_times = {};
  // Why the mixed_cells check (src/mixed_cells.hpp) does not apply to this
  // problem, reported with it; nullptr: it applies in remap mode.
  const char* mixed_cells_not_applicable = nullptr;
};

const std::vector<Problem>& problemRegistry();
// Throws ConfigError naming the unknown problem and the known ones.
const Problem& findProblem(const std::string& name);

// Helpers shared by the generators.
// Remap mode: the checks whose reference is the same in both modes (an exact
// solution) get it as their lagrange_reference; lagrange mode: nothing.
void setModeIndependentReferences(const Config& config, std::vector<Check>& checks);
// Throws ConfigError when the keys are declared for lagrange mode: the
// problem exists only in remap mode, for the reason `why`. In ALE mode it
// starts from the remap set-up (Config::useRemapSetup); call it before
// declaring any key.
void refuseLagrangeMode(Config& config, const std::string& problem, const std::string& why);
// The gas round the bodies of a remap set-up: gas.gamma, gas.rho, gas.p (an
// ideal gas at rest); throws ConfigError naming the problem for impossible values.
struct AmbientGas {
  MaterialParams material;
  double rho = 0.0, e = 0.0;  // density, specific internal energy p / ((gamma - 1) rho)
};
AmbientGas readAmbientGas(const Config& config, const std::string& problem);
void declareMeshKeys(Config& config, int nx, int ny, int nz);
void declareBoundaryKeys(Config& config, const std::array<const char*, kNumSides>& defaults);
// <prefix>.rho0, a0, Gamma0, s, mu, yield_stress and the hardening keys: a
// Mie-Gruneisen, hypo-elastic plastic solid, with the named preset's defaults.
void declareHypoSolidKeys(Config& config, const std::string& prefix, const std::string& preset);
MaterialParams readHypoSolid(const Config& config, const std::string& prefix,
                             const std::string& preset);
// <prefix>.hardening (perfect, linear, johnson_cook) and its parameters
// (docs/method.md §A7), with m's values as defaults; read into m.
void declareHardeningKeys(Config& config, const std::string& prefix, const MaterialParams& m);
void readHardening(const Config& config, const std::string& prefix, MaterialParams& m);
const char* hardeningName(HardeningKind kind);
// <prefix>.rho0, young, poisson: a Neo-Hookean hyper-elastic solid.
void declareNeoHookeanKeys(Config& config, const std::string& prefix, const std::string& preset);
MaterialParams readNeoHookean(const Config& config, const std::string& prefix,
                              const std::string& preset);
// Mean over the cells with a face on `side` of sigma_xx = -p + S_xx (solids'
// wall stress) or of the centroid coordinate `axis` (a tip position).
double sideMeanStressXX(const Mesh& mesh, const State& state, int side);
double sideMeanCentroid(const Mesh& mesh, const State& state, int side, int axis);
// bc.<side>.sigma_xx ... sigma_xz: the stress imposed on a traction side.
void declareTractionKeys(Config& config, int side, const SymMat3& stress);
SideBoundaries readBoundaries(const Config& config);
// Volumes and centroids of the cells on the host (same formulas as the kernels).
void hostCellShapes(const HostMesh& mesh, std::vector<double>& volume, std::vector<Vec3>& centroid);

// Host geometry of the initial cells, for the generators' initial state.
struct CellShapes {
  std::vector<double> volume;
  std::vector<Vec3> centroid;
};
// The mesh of a block [lo, hi] from the problem's mesh.n* and bc.* keys, with
// the given material table and the shapes of its cells; on a decomposed run,
// this rank's part of it (thisRanksPart): the generators compute each cell's
// initial state from its own geometry, so they fill the part alone.
// `mapping`: BlockSpec::mapping (the identity if empty).
ProblemSetup setupBlock(const Config& config, const Vec3& lo, const Vec3& hi,
                        std::vector<MaterialParams> materials, CellShapes& shapes,
                        std::function<Vec3(const Vec3&)> mapping = {});

// Initial state of a multi-material problem (remap mode): the material of
// each point, each material's uniform density and specific internal energy,
// and its velocity field.
struct MaterialRegions {
  std::function<int(const Vec3&)> material_at;
  std::vector<double> rho, e;  // per material
  std::function<Vec3(int material, const Vec3& x)> velocity;
};
// Fills setup.cells with mixed cells: volume fractions by sampling n^3 points
// per cell (midpoints of a regular grid of the reference cube, mapped
// trilinearly and weighted by the map's Jacobian); the cell velocity is the
// mass-weighted mean of the samples' velocities (momentum conserved).
void fillMaterialRegions(ProblemSetup& setup, const MaterialRegions& regions,
                         int samples_per_edge = 8);
// CSV rows of some cells (a row or a layer of the block), each line
// "global_id row" in `keyed_lines`: written to `out` in cell order, without
// the ids. With distributed fields rank 0 merges the ranks' lines as it
// writes them, a piece of each rank's at a time (parallel::writeMergedOnRoot;
// collective), and `out` is only written on rank 0.
void writeRowsInCellOrder(const std::string& keyed_lines, bool distributed, std::ostream& out);

// A result file of a problem's (its CSVs): the text is gathered here, then
// written whole by write(), which throws naming the file when it cannot be
// (writeTextFile: a directory standing there, a full disk): never silently
// missing or cut. With no path (a rank other than the first, or a run
// without files) write() does nothing.
class ResultFile : public std::ostringstream {
 public:
  explicit ResultFile(std::string path) : path_(std::move(path)) {}
  void write() const;

 private:
  std::string path_;
};
// Records (a few numbers each) that every rank made from its owned cells:
// all ranks' on every rank, in rank order, when the fields are distributed
// (collective); otherwise `mine`. For the few cells a check reads along a
// row or a ray, never for a field.
std::vector<double> recordsOfAllRanks(const FinalFields& fields, std::vector<double> mine);
// The in-plane corners (VTK nodes 0-3) and density of every cell, in cell
// order, to the CSV at `path` ("x0,y0,x1,y1,x2,y2,x3,y3,density"; the shape
// of a slab's deformed mesh). Collective with distributed fields; `path`
// is only written where it is not empty.
void writeCellOutlines(const std::string& path, const FinalFields& fields);
// Position along +x where the volume fraction of `material` falls through 0.5
// on the row of cells nearest to the line y = y_line, z = mid-thickness
// (linear interpolation between cell centroids), or NAN if it never does.
double materialFrontX(const FinalFields& fields, int material, double y_line);
// Probes' reductions (Probe::sample), left in the slots without waiting:
// a bar's or rod's length from material 0's volume in the row of cells along
// the x axis (those with a side on y = 0, and on z = 0 when z_axis_too), over
// each cell's cross-section, sum alpha v / (dy dz), a smooth measure (this
// rank's sum in slots.scalar); the largest node x (this rank's in
// slots.scalar: a body on the wall x = 0, its length); the mean over the
// cells with a face on `side` of sigma_xx = -p + S_xx or of the centroid's
// coordinate `axis` (this rank's sum and count in slots.sums). `label`: the
// kernel's.
void sampleMaterialLengthAlongAxis(const char* label, const Mesh& mesh, const State& state,
                                   bool z_axis_too, const ProbeSlots& slots);
void sampleLargestNodeX(const char* label, const Mesh& mesh, const ProbeSlots& slots);
void sampleSideMeanStressXX(const Mesh& mesh, const State& state, int side,
                            const ProbeSlots& slots);
void sampleSideMeanCentroid(const Mesh& mesh, const State& state, int side, int axis,
                            const ProbeSlots& slots);
// After the fence, over every rank (collective): the sum of slots.scalar, its
// largest, and the mean of slots.sums (sum over count; 0 with no cell).
double sumOverRanks(const ProbeSlots& slots);
double largestOverRanks(const ProbeSlots& slots);
double meanOverRanks(const ProbeSlots& slots);
// A ratio of the slots.sums over every rank, v[1] / v[0] (a centroid).
double ratioOverRanks(const ProbeSlots& slots);
// The outermost place where a volume fraction falls through 1/2 along a row
// of cells: `mine` holds this rank's (coordinate, alpha) pairs, gathered
// from every rank (collective with distributed fields), sorted, and the last
// crossing interpolated linearly between centroids; NAN if none.
double outwardHalfCrossing(const FinalFields& fields, const std::vector<double>& mine);
// Where the volume fraction of `material` crosses 1/2 along the ray
// origin + s direction (s >= 0, direction in the x-y plane) through a slab one
// cell thick on a uniform block mesh: the cell values are interpolated
// bilinearly between centroids (constant beyond the outer ones) and sampled
// every 1/8 of a cell until the ray leaves the block, in order of s.
struct AlphaCrossing {
  double distance;  // s at the crossing (linear between samples)
  bool rising;      // alpha increases through 1/2 along the ray
};
std::vector<AlphaCrossing> alphaCrossingsAlongRay(const FinalFields& fields, int material,
                                                  const Vec3& origin, const Vec3& direction);

}  // namespace lagremap
