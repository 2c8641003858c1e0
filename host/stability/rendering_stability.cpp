// The stability suite's rendering family (stability_case.h): one scene per failure mode of the shadow and
// refraction methods, every device method on it, measured against the exact Embree references at the same
// pixels through eval/reference_comparison.h (shadows: transmittance at the visible receivers,
// metrics/shadow_receivers.h; refraction: the matched reference image and paths,
// metrics/refraction_metrics.h, each method's frame shaded with the exact shadows so the error is
// refraction's alone).
//
// Bounds state requirements, each row with its reason (stability_case.h):
//   physics       no non-finite pixel; total internal reflection present in the reference of the TIR scene;
//   targets       voxel-exact: issue 19's (image RMSE <= 0.01, event mismatch <= 1 %, transmittance RMSE
//                 <= 0.005); voxel-multi on walls of 4 voxels or more: kThinWallRmse (issue 19);
//   purpose       every other method's transmittance RMSE must be below that of no shadow at all
//                 (transmittance 1 at the same receivers), its image RMSE below that of the glass drawn
//                 unrefracted (--refraction none, exact shadows): a method that does worse than leaving the
//                 effect out has no purpose; both baselines are measured on the case itself;
//   rules         the approximate methods' event mismatch at most 0.5 (they follow the interfaces they find),
//                 TIR found at least 0.5 (every method mirrors on TIR), acne at most 0.05 (the suite's 'off'
//                 threshold), leaks under a closed slab at most 0.1;
//   documented    known failures, two-sided (kBounds' low to bound, the measured values / 1.5 to x 1.5 within
//                 [0, 1]): walls under 2 voxels for the voxel methods, two interfaces for voxel-two and
//                 image-space, shells under a voxel, each case's own failure mode where a method shows it.
// A method or measure without a bound it needs is an error when the cases are built
// (rendering_stability_cases), never a silent default. The refraction cases before the thin-wall family
// run on the whole scene's grid (RefractionGrid::kScene), on which their bounds were measured; the thin-wall
// family runs on the fitted grid.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene.h"
#include "eval/reference_comparison.h"
#include "eval/render_case.h"
#include "io/image_file.h"
#include "metrics/image_metrics.h"
#include "metrics/refraction_metrics.h"
#include "reference/reference_refraction.h"
#include "render/environment_map.h"
#include "render/frame_renderer.h"
#include "render/render_scene.h"
#include "render/voxel_refraction.h"
#include "stability/stability_case.h"
#include "util/error.h"

namespace voxr {

namespace {

constexpr const char* kFamily = "rendering";

// Image size and grids of the two versions: the small one the test suite runs, the full one of
// `voxr bench stability`.
struct Version {
  uint32_t width, height;
  uint32_t shadow_resolution;      // RenderOptions::shadow_resolution
  uint32_t refraction_resolution;  // RefractionOptions::resolution
};
Version version(bool full) {
  return full ? Version{640, 480, 256, 256} : Version{96, 72, 64, 64};
}

// ---- Bounds ----

// voxel-multi's image RMSE on a wall of 4 voxels or more of the fitted grid: a requirement, issue 19's target
// for the papers' method on thin-walled scenes. Why 4: the voxels a plane touches (conservative) have their
// centres within (|nx| + |ny| + |nz|) / 2 <= sqrt(3) / 2 voxel of it, so the boundary runs of a wall w voxels
// thick have centres at least w - sqrt(3) apart: at 4, 2.27 voxels, beyond the 1.5-voxel reach of the smooth
// normal's weights, so neither the voxel nor the smooth normals of one surface mix with the other's; the
// path meets every interface the reference meets and what is left is the normals' and positions'
// discretisation. Under 2 voxels the runs touch or share voxels and the normals cancel.
constexpr double kThinWallRmse = 0.08;

// Transmittance RMSE of every light-grid shadow method (voxel, uniform, filter, opaque) where issue 20 sets
// the target: a floor under a light 1-3 degrees above the horizon is no caster of itself (a plane cannot
// shadow itself: exactly 1 at every receiver, so 0.02 is the issue's allowance, not a measurement), and a
// point light 1e5 units up must keep a sphere's shadow (0.05). voxel-exact keeps its own requirement, 0.005.
// With a box on the floor at 3 degrees its shadow must stay and the floor stay lit: 0.1, where no shadow at
// all measures >= 0.25 (tests/light_grid_shadows_test.cpp) and the floor shadowing itself 0.31; what remains
// is the shadow's two long edges, blurred over one light-grid column (0.04, conservative mode 0.08 at 96 x
// 72).
constexpr double kGrazingFloorRmse = 0.02;
constexpr double kFloorBoxRmse = 0.1;
constexpr double kFarPointLightRmse = 0.05;
constexpr double kVoxelExactShadowRmse = 0.005;

// Measures with a bound in kBounds (the key). kShadowRmse and kImageRmse rows absent from it are bounded by
// their purpose's baseline, measured on the case.
enum class Measure { kShadowRmse, kAcne, kLeak, kImageRmse, kEventMismatch, kTirFound };

// The reasons of kBounds' rows (StabilityRow::reason).
constexpr std::string_view kExactTarget =
    "issue 19 target: voxel-exact image RMSE <= 0.01 (PSNR >= 40 dB), event mismatch <= 1 %, the reference's "
    "TIR";
constexpr std::string_view kExactShadowTarget =
    "issue 19 target: voxel-exact transmittance RMSE <= 0.005 against the reference it reproduces";
constexpr std::string_view kThinWallTarget =
    "issue 19 target: voxel-multi image RMSE <= 0.08 on walls of 4 voxels or more (kThinWallRmse)";
constexpr std::string_view kRuleEvents =
    "rule: the method follows the interfaces it finds (refraction.h's model), so most event sequences match "
    "the reference's: at most 0.5";
constexpr std::string_view kRuleTir =
    "rule: every method mirrors on total internal reflection (refraction.h), so at least half the "
    "reference's TIR pixels show it";
constexpr std::string_view kRuleAcne =
    "rule: a lit receiver is not darkened by its own voxels beyond the suite's 0.05 'off' threshold (RMSE)";
constexpr std::string_view kRuleLeak =
    "rule: a closed opaque slab stops the light: mean transmittance under it at most 0.1 (the small "
    "version's slab is under one light-grid voxel)";
constexpr std::string_view kDocGemEvents =
    "documented failure: a faceted gem's rays reflect totally several times and voxel normals at facet edges "
    "send them on other paths; measured / 1.5 to x 1.5";
constexpr std::string_view kDocTouching =
    "documented failure: two dielectrics within one voxel share boundary voxels (the case's failure mode); "
    "measured / 1.5 to x 1.5";
constexpr std::string_view kDocTwoSurfaces =
    "documented failure: image-space refracts at two surfaces by design (Wyman 2005) where paths here meet "
    "more; measured / 1.5 to x 1.5";
constexpr std::string_view kDocCorners =
    "documented failure: rays slip between voxels that touch at corners (the case's failure mode); measured "
    "/ 1.5 to x 1.5";
constexpr std::string_view kDocSearchStep =
    "documented failure: surfaces closer than a search step along a ray are skipped (docs/methods.md, "
    "distance maps); measured / 1.5 to x 1.5";
constexpr std::string_view kDocThinForMaps =
    "documented failure: a wall thinner than the maps' search step and texel footprint (under 2 voxels of "
    "the fitted grid here) has its surfaces skipped (docs/methods.md, distance maps); measured / 1.5 to x "
    "1.5";
constexpr std::string_view kDocFilterAcne =
    "documented failure: the filter's pre-filtered opacity darkens the lit leaf (the bias it trades against "
    "leaks); measured / 1.5 to x 1.5";
constexpr std::string_view kDocShells =
    "documented failure: walls under a voxel cancel the voxel normals and hide the inner shell from "
    "image-space and voxel-two: every event sequence differs (at least 0.9)";
constexpr std::string_view kDocShellsMulti =
    "documented failure: voxel-multi misses crossings of a shell's walls under a voxel (their boundary runs "
    "merge), so many event sequences differ (0.83 small, 0.45 full); measured / 1.5 to 1";
constexpr std::string_view kDocUnderTwoVoxels =
    "documented failure: under 2 voxels a wall's two surfaces share boundary voxels (outside the voxel "
    "methods' domain); measured / 1.5 to x 1.5";
constexpr std::string_view kDocOverShadow =
    "documented failure: above no shadow's error: conservative voxels (or the filter's blur along a grazing "
    "view) darken lit receivers; measured / 1.5 to x 1.5";
constexpr std::string_view kDocWorseThanUnrefracted =
    "documented failure: image RMSE above the glass drawn unrefracted (RMSE favours a smooth wrong picture "
    "over misplaced detail); measured / 1.5 to x 1.5";
constexpr std::string_view kDocTwoInterfaces =
    "documented failure: voxel-two meets two interfaces by design where the vase has four; measured / 1.5 to "
    "x 1.5";

struct Bound {
  std::string_view case_name, method;
  Measure measure;
  double small, full;  // the bound of each version (at most, or at least for kTirFound)
  std::string_view reason;
  double low = -std::numeric_limits<double>::infinity();  // a documented failure's lower end (both versions)
};

// Each line's comment holds the values measured (small version first) on PoCL (2-core CPU, shared).
// clang-format off
constexpr Bound kBounds[] = {
    // Approximate methods whose error is above the purpose baseline (no shadow; glass unrefracted) on these
    // cases: documented failures (2026-12-02: the baselines measured on the small version were 0.139, 0.190,
    // 0.259, 0.049, 0.295 for the shadow cases, 0.080 to 0.107 for the refraction ones).
    {"grazing-view", "filter", Measure::kShadowRmse, 0.13, 0.13, kDocOverShadow, 0.0557},  // 0.08361, 0.08481
    {"receivers-among-casters", "voxel-conservative", Measure::kShadowRmse, 0.5, 0.5, kDocOverShadow, 0.154},  // 0.3305, 0.232
    {"total-internal-reflection", "voxel-multi", Measure::kImageRmse, 0.14, 0.14, kDocWorseThanUnrefracted, 0.058},  // 0.08702, 0.09264
    {"total-internal-reflection", "voxel-two", Measure::kImageRmse, 0.17, 0.17, kDocWorseThanUnrefracted, 0.0727},  // 0.1091, 0.1133
    {"total-internal-reflection", "image-space", Measure::kImageRmse, 0.151, 0.151, kDocWorseThanUnrefracted, 0.0621},  // 0.1004, 0.09322
    {"nested-thin-shells", "voxel-multi", Measure::kImageRmse, 0.148, 0.148, kDocWorseThanUnrefracted, 0.0642},  // 0.09877, 0.09626
    {"nested-thin-shells", "voxel-two", Measure::kImageRmse, 0.15, 0.15, kDocWorseThanUnrefracted, 0.0652},  // 0.1001, 0.09777
    {"multi-material/ball-figure", "image-space", Measure::kImageRmse, 0.215, 0.215, kDocWorseThanUnrefracted, 0.0952},  // 0.1428, 0.1433
    {"multi-material/touching", "voxel-two", Measure::kImageRmse, 0.133, 0.133, kDocWorseThanUnrefracted, 0.0533},  // 0.08879, 0.07993
    {"thin-wall/2", "voxel-multi", Measure::kImageRmse, 0.11, 0.11, kDocWorseThanUnrefracted, 0.0395},  // 0.07346, 0.0592
    {"thin-wall/2", "voxel-two", Measure::kImageRmse, 0.11, 0.11, kDocWorseThanUnrefracted, 0.0407},  // 0.07347, 0.061
    {"thin-wall/4", "voxel-two", Measure::kImageRmse, 0.108, 0.108, kDocWorseThanUnrefracted, 0.0378},  // 0.07202, 0.0567
    {"thin-wall/0.5", "distance-maps", Measure::kImageRmse, 0.19, 0.19, kDocThinForMaps, 0.037},  // 0.05546, 0.1263
    {"thin-wall/1", "distance-maps", Measure::kImageRmse, 0.148, 0.148, kDocThinForMaps, 0.0409},  // 0.06134, 0.0988
    {"thin-wall/4", "distance-maps", Measure::kImageRmse, 0.103, 0.103, kDocWorseThanUnrefracted, 0.04},  // 0.06898, 0.06
    {"thin-wall/8", "voxel-two", Measure::kImageRmse, 0.0996, 0.0996, kDocWorseThanUnrefracted, 0.0378},  // 0.06642, 0.0567
    {"thin-wall/8", "distance-maps", Measure::kImageRmse, 0.104, 0.104, kDocWorseThanUnrefracted, 0.0406},  // 0.06933, 0.0609
    {"sheet-self-shadowing", "voxel-center", Measure::kAcne, 0.05, 0.05, kRuleAcne},  // 0, 0
    {"sheet-self-shadowing", "voxel-center", Measure::kLeak, 0.1, 0.1, kRuleLeak},  // 0.04954, 0.007841
    {"sheet-self-shadowing", "voxel-conservative", Measure::kAcne, 0.05, 0.05, kRuleAcne},  // 1.009e-06, 7.249e-07
    {"sheet-self-shadowing", "voxel-conservative", Measure::kLeak, 0.1, 0.1, kRuleLeak},  // 0.003884, 0.0002077
    {"sheet-self-shadowing", "uniform", Measure::kAcne, 0.05, 0.05, kRuleAcne},  // 0, 0
    {"sheet-self-shadowing", "uniform", Measure::kLeak, 0.1, 0.1, kRuleLeak},  // 0.04954 (uniform blocks with opaque casters since issue 20 kind 4)
    {"sheet-self-shadowing", "filter", Measure::kAcne, 0.71, 0.71, kDocFilterAcne, 0.309},  // 0.4632, 0.4712
    {"sheet-self-shadowing", "filter", Measure::kLeak, 0.1, 0.1, kRuleLeak},  // 0.04954, 0.007841
    {"sheet-self-shadowing", "opaque", Measure::kAcne, 0.05, 0.05, kRuleAcne},  // 6.915e-09, 5.62e-09
    {"sheet-self-shadowing", "opaque", Measure::kLeak, 0.1, 0.1, kRuleLeak},  // 0.04954, 0.007841
    // voxel-exact: requirements, not 1.5x a measurement — the issue's target (transmittance RMSE <= 0.005
    // against the reference it reproduces) and the suite's floor for acne and leaks; measured 0 on the small
    // cases (2026-12-02, PoCL), the full ones not run yet.
    {"grazing-light/80", "voxel-exact", Measure::kShadowRmse, 0.005, 0.005, kExactShadowTarget},  // 0, not run
    {"grazing-light/85", "voxel-exact", Measure::kShadowRmse, 0.005, 0.005, kExactShadowTarget},  // 0, not run
    {"grazing-light/88", "voxel-exact", Measure::kShadowRmse, 0.005, 0.005, kExactShadowTarget},  // 0, not run
    {"grazing-view", "voxel-exact", Measure::kShadowRmse, 0.005, 0.005, kExactShadowTarget},  // 0, not run
    {"receivers-among-casters", "voxel-exact", Measure::kShadowRmse, 0.005, 0.005, kExactShadowTarget},  // 0, not run
    {"sheet-self-shadowing", "voxel-exact", Measure::kShadowRmse, 0.005, 0.005, kExactShadowTarget},  // 0, not run
    {"sheet-self-shadowing", "voxel-exact", Measure::kAcne, 0.005, 0.005, kExactShadowTarget},  // 0, not run
    {"sheet-self-shadowing", "voxel-exact", Measure::kLeak, 0.005, 0.005, kExactShadowTarget},  // 0, not run
    {"total-internal-reflection", "voxel-multi", Measure::kEventMismatch, 0.73, 0.73, kDocGemEvents, 0.24},  // 0.375, 0.4862
    {"total-internal-reflection", "voxel-multi", Measure::kTirFound, 0.5, 0.5, kRuleTir},  // 0.6689, 0.6744
    {"total-internal-reflection", "voxel-two", Measure::kEventMismatch, 0.71, 0.71, kDocGemEvents, 0.25},  // 0.3878, 0.4721
    {"total-internal-reflection", "voxel-two", Measure::kTirFound, 0.5, 0.5, kRuleTir},  // 0.6689, 0.6744
    {"total-internal-reflection", "image-space", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.398, 0.3842
    {"total-internal-reflection", "image-space", Measure::kTirFound, 0.5, 0.5, kRuleTir},  // 0.9522, 0.9924
    {"total-internal-reflection", "distance-maps", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.05541, 0.05404
    {"total-internal-reflection", "distance-maps", Measure::kTirFound, 0.5, 0.5, kRuleTir},  // 0.9829, 0.9807
    // Documented: walls under a voxel thick cancel the voxel normals and hide the inner shell from image-space
    // and voxel-two: every event sequence differs (held at 0.9 or more); voxel-multi misses inner crossings.
    {"nested-thin-shells", "voxel-multi", Measure::kEventMismatch, 1, 1, kDocShellsMulti, 0.3},  // 0.8292, 0.4499 (media by winding; 0.9913, 0.9978 by parity)
    {"nested-thin-shells", "voxel-two", Measure::kEventMismatch, 1, 1, kDocShells, 0.9},  // 1, 1
    {"nested-thin-shells", "image-space", Measure::kEventMismatch, 1, 1, kDocShells, 0.9},  // 1, 1
    {"nested-thin-shells", "distance-maps", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.01592, 0.01249
    {"grazing-slab", "voxel-multi", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.3925, 0.2803
    {"grazing-slab", "voxel-two", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.3737, 0.3039
    {"grazing-slab", "image-space", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.302, 0.3029
    {"grazing-slab", "distance-maps", Measure::kEventMismatch, 0.96, 0.96, kDocSearchStep, 0.41},  // 0.6333, 0.6387
    {"voxel-corners", "voxel-multi", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.382, 0.1272
    {"voxel-corners", "voxel-two", Measure::kEventMismatch, 0.76, 0.76, kDocCorners, 0.25},  // 0.5065, 0.3752
    {"voxel-corners", "image-space", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.355, 0.3361
    {"voxel-corners", "distance-maps", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.04221, 0.02357
    {"multi-material/ball-figure", "voxel-multi", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.3929, 0.1942
    {"multi-material/ball-figure", "voxel-two", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.4414, 0.2133
    {"multi-material/ball-figure", "image-space", Measure::kEventMismatch, 1, 1, kDocTwoSurfaces, 0.47},  // 0.7048, 0.7113
    {"multi-material/ball-figure", "distance-maps", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.3799, 0.3862
    {"multi-material/touching", "voxel-multi", Measure::kEventMismatch, 0.743, 0.743, kDocTouching, 0.18},  // 0.4946, 0.2708
    {"multi-material/touching", "voxel-two", Measure::kEventMismatch, 1, 1, kDocTouching, 0.39},  // 0.6831, 0.5883
    {"multi-material/touching", "image-space", Measure::kEventMismatch, 1, 1, kDocTwoSurfaces, 0.44},  // 0.673, 0.666
    {"multi-material/touching", "distance-maps", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.2451, 0.2331
    // The thin-wall family, measured 2026-12-02 (small version and full at 640 x 480, grid 256), fitted grid.
    // Voxel methods under 2 voxels: outside their domain (the wall's two surfaces share boundary voxels, whose
    // normals cancel or merge), documented from the measured values. voxel-two meets two interfaces by design
    // where the vase has four: its event mismatch is documented. voxel-multi from 4 voxels: kThinWallRmse.
    // The other image RMSEs: the purpose baseline.
    {"thin-wall/0.5", "voxel-multi", Measure::kImageRmse, 0.138, 0.138, kDocUnderTwoVoxels, 0.06},  // 0.09048, 0.092
    {"thin-wall/0.5", "voxel-multi", Measure::kEventMismatch, 1, 1, kDocUnderTwoVoxels, 0.475},  // 0.7132, 0.8008
    {"thin-wall/0.5", "voxel-two", Measure::kImageRmse, 0.122, 0.122, kDocUnderTwoVoxels, 0.053},  // 0.08127, 0.0793
    {"thin-wall/0.5", "voxel-two", Measure::kEventMismatch, 1, 1, kDocUnderTwoVoxels, 0.607},  // 0.9102, 0.914
    {"thin-wall/0.5", "image-space", Measure::kEventMismatch, 1, 1, kDocTwoSurfaces, 0.54},  // 0.8117, 0.8177
    {"thin-wall/0.5", "distance-maps", Measure::kEventMismatch, 1, 1, kDocThinForMaps, 0.148},  // 0.2307, 0.8853
    {"thin-wall/1", "voxel-multi", Measure::kImageRmse, 0.126, 0.126, kDocUnderTwoVoxels, 0.05},  // 0.07517, 0.0839
    {"thin-wall/1", "voxel-multi", Measure::kEventMismatch, 0.801, 0.801, kDocUnderTwoVoxels, 0.271},  // 0.4065, 0.5343
    {"thin-wall/1", "voxel-two", Measure::kImageRmse, 0.114, 0.114, kDocUnderTwoVoxels, 0.049},  // 0.07611, 0.0736
    {"thin-wall/1", "voxel-two", Measure::kEventMismatch, 1, 1, kDocUnderTwoVoxels, 0.56},  // 0.8404, 0.8401
    {"thin-wall/1", "image-space", Measure::kEventMismatch, 1, 1, kDocTwoSurfaces, 0.54},  // 0.808, 0.8175
    {"thin-wall/1", "distance-maps", Measure::kEventMismatch, 0.645, 0.645, kDocThinForMaps, 0.154},  // 0.2444, 0.4301
    {"thin-wall/2", "voxel-multi", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.2606, 0.176
    {"thin-wall/2", "voxel-two", Measure::kEventMismatch, 1, 1, kDocTwoInterfaces, 0.539},  // 0.8092, 0.8209
    {"thin-wall/2", "image-space", Measure::kEventMismatch, 1, 1, kDocTwoSurfaces, 0.54},  // 0.808, 0.8186
    {"thin-wall/2", "distance-maps", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.2681, 0.2369
    {"thin-wall/4", "voxel-multi", Measure::kImageRmse, kThinWallRmse, kThinWallRmse, kThinWallTarget},  // 0.07091, 0.0503
    {"thin-wall/4", "voxel-multi", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.2045, 0.1325
    {"thin-wall/4", "voxel-two", Measure::kEventMismatch, 1, 1, kDocTwoInterfaces, 0.545},  // 0.8204, 0.8179
    {"thin-wall/4", "image-space", Measure::kEventMismatch, 1, 1, kDocTwoSurfaces, 0.54},  // 0.8304, 0.821
    {"thin-wall/4", "distance-maps", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.3204, 0.2557
    {"thin-wall/8", "voxel-multi", Measure::kImageRmse, kThinWallRmse, kThinWallRmse, kThinWallTarget},  // 0.0619, 0.051
    {"thin-wall/8", "voxel-multi", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.2494, 0.1417
    {"thin-wall/8", "voxel-two", Measure::kEventMismatch, 1, 1, kDocTwoInterfaces, 0.53},  // 0.7943, 0.8172
    {"thin-wall/8", "image-space", Measure::kEventMismatch, 1, 1, kDocTwoSurfaces, 0.54},  // 0.8529, 0.827
    {"thin-wall/8", "distance-maps", Measure::kEventMismatch, 0.5, 0.5, kRuleEvents},  // 0.3628, 0.2669
    // voxel-exact: requirements, not measurements (issue 19: PSNR >= 40 dB, i.e. image RMSE <= 0.01, and event
    // mismatch <= 1 % against the matched reference; its TIR is the reference's). Small version measured
    // 2026-12-02 (image RMSE, event mismatch) in the comments; the full one not yet.
    {"total-internal-reflection", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},  // 5.737e-06
    {"total-internal-reflection", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},  // 0
    {"total-internal-reflection", "voxel-exact", Measure::kTirFound, 0.99, 0.99, kExactTarget},  // 1
    {"nested-thin-shells", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},  // 1.195e-05
    {"nested-thin-shells", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},  // 0
    {"grazing-slab", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},  // 0.003134
    {"grazing-slab", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},  // 0.0006959
    {"voxel-corners", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},  // 2.727e-07
    {"voxel-corners", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},  // 0
    {"multi-material/ball-figure", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},  // 4.604e-06
    {"multi-material/ball-figure", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},  // 0
    {"multi-material/touching", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},  // 0.007103
    {"multi-material/touching", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},  // 0.002901
    // voxel-exact on the thin walls (it had none: the case's loosest, infinite, was used silently).
    {"thin-wall/0.5", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},
    {"thin-wall/0.5", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},
    {"thin-wall/1", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},
    {"thin-wall/1", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},
    {"thin-wall/2", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},
    {"thin-wall/2", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},
    {"thin-wall/4", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},
    {"thin-wall/4", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},
    {"thin-wall/8", "voxel-exact", Measure::kImageRmse, 0.01, 0.01, kExactTarget},
    {"thin-wall/8", "voxel-exact", Measure::kEventMismatch, 0.01, 0.01, kExactTarget},
};
// clang-format on

// kBounds' row of `measure` for `method` on case `name`, if any.
const Bound* find_bound(std::string_view name, std::string_view method, Measure measure) {
  for (const Bound& b : kBounds)
    if (b.case_name == name && b.method == method && b.measure == measure) return &b;
  return nullptr;
}

StabilityRow row(const std::string& name, const std::string& method, const std::string& measure, double value,
                 double bound, bool at_least, std::string note, std::string reason) {
  return stability_row(kFamily, name, method, measure, value, bound, at_least, std::move(note),
                       std::move(reason));
}

// A row bounded by kBounds (which must hold it: rendering_stability_cases checks when it builds the cases);
// without a row there, a purpose baseline (`baseline` and its reason) where the measure has one.
StabilityRow measured_row(const std::string& name, const std::string& method, const std::string& measure,
                          Measure key, double value, bool full, std::string note, bool at_least = false,
                          std::optional<std::pair<double, std::string>> baseline = std::nullopt) {
  // NaN never passes: value <= bound and value >= bound are both false.
  if (const Bound* b = find_bound(name, method, key)) {
    StabilityRow r = row(name, method, measure, value, full ? b->full : b->small, at_least, std::move(note),
                         std::string(b->reason));
    r.low = b->low;
    return r;
  }
  if (!baseline) fail("rendering_stability.cpp: no bound for {} on case {}", method, name);
  return row(name, method, measure, value, baseline->first, false, std::move(note), baseline->second);
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// ---- Scenes ----

// A case built from scene-format JSON (core/scene.h): `edit` may change the parsed scene (the light's angle)
// before it is placed (eval/render_case.h). Throws voxr::Error from parse_scene.
std::unique_ptr<RenderCase> make_scene(const std::string& name, std::string_view json, const Version& v,
                                       const std::function<void(Scene&)>& edit = {}) {
  Scene scene = parse_scene(json, "stability case " + name, ".");
  if (edit) edit(scene);
  return std::make_unique<RenderCase>(std::move(scene), v.width, v.height);
}

// A floor (opaque), a low opaque box and a leaf (sheet) casting onto it: the grazing cases' scene.
constexpr std::string_view kGrazingScene = R"({
  "materials": [
    {"name": "floor", "kind": "opaque", "color": [0.75, 0.75, 0.72]},
    {"name": "stone", "kind": "opaque", "color": [0.6, 0.6, 0.65]},
    {"name": "leaf", "kind": "sheet", "color": [0.35, 0.6, 0.2], "transmittance": [0.5, 0.75, 0.4]}
  ],
  "meshes": [
    {"generator": "plane", "params": {"size": [6, 6], "subdivisions": 1}, "material": "floor"},
    {"generator": "box", "params": {"lo": [-0.15, 0, -0.15], "hi": [0.15, 0.2, 0.15]}, "material": "stone",
     "transform": {"rotate_deg": [0, 20, 0], "translate": [-1.2, 0, -0.4]}},
    {"generator": "plane", "params": {"size": [0.5, 0.5], "subdivisions": 1}, "material": "leaf",
     "transform": {"rotate_deg": [25, 10, 0], "translate": [-1.0, 0.2, 0.5]}}
  ],
  "light": {"type": "directional", "direction": [0.7, -0.7, 0], "intensity": [1.2, 1.2, 1.2]},
  "camera": {"position": [0.5, 3.0, 3.5], "look_at": [0.5, 0, 0], "fov_deg": 45, "width": 640,
             "height": 480},
  "environment": {"color": [0.3, 0.35, 0.4]}
})";

// A lone 6 x 6 floor (r03_grazing_floor.json): the grazing-floor cases light it 1 to 3 degrees above the
// horizon.
constexpr std::string_view kLoneFloorScene = R"({
  "materials": [{"name": "floor", "kind": "opaque", "color": [0.7, 0.7, 0.65]}],
  "meshes": [{"generator": "plane", "params": {"size": [6, 6]}, "material": "floor"}],
  "light": {"type": "directional", "direction": [1, -0.05, 0.3], "intensity": [1, 1, 1]},
  "camera": {"position": [0, 3, 3.5], "look_at": [0, 0.3, 0], "fov_deg": 45, "width": 640, "height": 480},
  "environment": {"color": [0.2, 0.2, 0.2]}
})";

// The lone floor with a box 0.6 high on it, whose shadow at grazing light reaches across the floor.
constexpr std::string_view kFloorBoxScene = R"({
  "materials": [{"name": "floor", "kind": "opaque", "color": [0.7, 0.7, 0.65]},
                {"name": "stone", "kind": "opaque", "color": [0.6, 0.6, 0.65]}],
  "meshes": [{"generator": "plane", "params": {"size": [6, 6]}, "material": "floor"},
             {"generator": "box", "params": {"lo": [-1.6, 0, -0.4], "hi": [-1.0, 0.6, 0.4]}, "material": "stone"}],
  "light": {"type": "directional", "direction": [1, -0.05, 0.3], "intensity": [1, 1, 1]},
  "camera": {"position": [0, 3, 3.5], "look_at": [0, 0.3, 0], "fov_deg": 45, "width": 640, "height": 480},
  "environment": {"color": [0.2, 0.2, 0.2]}
})";

// A red sphere over a floor under a point light 1e5 units up (r03_far_point_light.json).
constexpr std::string_view kFarPointLightScene = R"({
  "materials": [{"name": "floor", "kind": "opaque", "color": [0.8, 0.8, 0.8]},
                {"name": "red", "kind": "opaque", "color": [0.8, 0.2, 0.2]}],
  "meshes": [{"generator": "plane", "params": {"size": [6, 6]}, "material": "floor"},
             {"generator": "sphere", "params": {"radius": 0.5}, "material": "red",
              "transform": {"translate": [0, 0.6, 0]}}],
  "light": {"type": "point", "position": [0, 100000, 0], "intensity": [1e10, 1e10, 1e10]},
  "camera": {"position": [0, 2, 4], "look_at": [0, 0.4, 0], "fov_deg": 45, "width": 640, "height": 480},
  "environment": {"color": [0.3, 0.3, 0.3]}
})";

// The foliage scene's block of leaves with an opaque ball and box among them (data/scenes/foliage.json).
constexpr std::string_view kFoliageScene = R"({
  "materials": [
    {"name": "leaf", "kind": "sheet", "color": [0.35, 0.6, 0.2], "transmittance": [0.5, 0.75, 0.4]},
    {"name": "clay", "kind": "opaque", "color": [0.8, 0.35, 0.2]},
    {"name": "stone", "kind": "opaque", "color": [0.6, 0.6, 0.65]},
    {"name": "floor", "kind": "opaque", "color": [0.75, 0.75, 0.72]}
  ],
  "meshes": [
    {"generator": "plane", "params": {"size": [8, 8], "subdivisions": 1}, "material": "floor"},
    {"generator": "foliage", "params": {"size": [3, 1.2, 3], "density": 300, "leaf_size": 0.12, "seed": 3},
     "material": "leaf", "transform": {"translate": [0, 1.2, 0]}},
    {"generator": "sphere", "params": {"radius": 0.3, "stacks": 16, "slices": 32}, "material": "clay",
     "transform": {"translate": [0.4, 1.2, 0.3]}},
    {"generator": "box", "params": {"lo": [-0.25, -0.25, -0.25], "hi": [0.25, 0.25, 0.25]},
     "material": "stone", "transform": {"rotate_deg": [0, 30, 0], "translate": [-0.7, 1.0, -0.5]}}
  ],
  "light": {"type": "directional", "direction": [-0.35, -1, -0.25], "intensity": [1.4, 1.4, 1.4]},
  "camera": {"position": [0, 2.6, 5.5], "look_at": [0, 1.0, 0], "fov_deg": 45, "width": 640, "height": 480},
  "environment": {"color": [0.3, 0.35, 0.4]}
})";

// A lit leaf (sheet) facing the light and the camera, and a closed opaque slab 0.04 thick (under one voxel
// of the small version's light grid) over the floor.
constexpr std::string_view kSheetScene = R"({
  "materials": [
    {"name": "floor", "kind": "opaque", "color": [0.75, 0.75, 0.72]},
    {"name": "leaf", "kind": "sheet", "color": [0.35, 0.6, 0.2], "transmittance": [0.5, 0.75, 0.4]},
    {"name": "stone", "kind": "opaque", "color": [0.6, 0.6, 0.65]}
  ],
  "meshes": [
    {"generator": "plane", "params": {"size": [5, 5], "subdivisions": 1}, "material": "floor"},
    {"generator": "plane", "params": {"size": [1.4, 1.4], "subdivisions": 1}, "material": "leaf",
     "transform": {"rotate_deg": [50, 0, 0], "translate": [-0.9, 0.9, 0]}},
    {"generator": "box", "params": {"lo": [-0.6, -0.02, -0.6], "hi": [0.6, 0.02, 0.6]}, "material": "stone",
     "transform": {"rotate_deg": [0, 15, 0], "translate": [1.0, 0.7, 0]}}
  ],
  "light": {"type": "directional", "direction": [0.2, -1, -0.6], "intensity": [1.2, 1.2, 1.2]},
  "camera": {"position": [0, 2.8, 4.0], "look_at": [0, 0.4, 0], "fov_deg": 45, "width": 640, "height": 480},
  "environment": {"color": [0.3, 0.35, 0.4]}
})";

// data/scenes/gem.json: a faceted gem of IOR 2.42 (diamond) on a floor.
constexpr std::string_view kGemScene = R"({
  "materials": [
    {"name": "diamond", "kind": "dielectric", "ior": 2.42, "absorption": [0.02, 0.02, 0.02]},
    {"name": "floor", "kind": "opaque", "color": [0.6, 0.58, 0.55]}
  ],
  "meshes": [
    {"generator": "sphere", "params": {"radius": 1.0, "stacks": 4, "slices": 8}, "material": "diamond",
     "transform": {"scale": [1.0, 0.7, 1.0], "rotate_deg": [0, 11, 0], "translate": [0, 0.8, 0]}},
    {"generator": "plane", "params": {"size": [8, 8], "subdivisions": 1}, "material": "floor"}
  ],
  "light": {"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.8, 0.8, 0.8]},
  "camera": {"position": [0, 2.0, 3.6], "look_at": [0, 0.75, 0], "fov_deg": 40, "width": 640, "height": 480},
  "environment": {"procedural": "checker"}
})";

// data/scenes/thin-shell.json: glass walls 0.03 thick, nested spheres: two boundaries within a voxel.
constexpr std::string_view kThinShellScene = R"({
  "materials": [
    {"name": "glass", "kind": "dielectric", "ior": 1.5, "absorption": [0.4, 0.2, 0.1]},
    {"name": "floor", "kind": "opaque", "color": [0.6, 0.58, 0.55]}
  ],
  "meshes": [
    {"generator": "sphere", "params": {"radius": 1.0, "stacks": 48, "slices": 96}, "material": "glass",
     "transform": {"translate": [0, 1.05, 0]}},
    {"generator": "sphere", "params": {"radius": 0.97, "stacks": 48, "slices": 96, "inward": true},
     "material": "glass",
     "transform": {"translate": [0, 1.05, 0]}},
    {"generator": "plane", "params": {"size": [8, 8], "subdivisions": 1}, "material": "floor"}
  ],
  "light": {"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.8, 0.8, 0.8]},
  "camera": {"position": [0, 1.6, 4.8], "look_at": [0, 1.0, 0], "fov_deg": 40, "width": 640, "height": 480},
  "environment": {"procedural": "checker"}
})";

// A glass slab 0.12 thick seen at 8 degrees from its plane: rays run along its faces through many boundary
// voxels.
constexpr std::string_view kGrazingSlabScene = R"({
  "materials": [
    {"name": "glass", "kind": "dielectric", "ior": 1.5, "absorption": [0.2, 0.1, 0.05]},
    {"name": "floor", "kind": "opaque", "color": [0.6, 0.58, 0.55]}
  ],
  "meshes": [
    {"generator": "box", "params": {"lo": [-1.5, 0.4, -1.5], "hi": [1.5, 0.52, 1.5]}, "material": "glass"},
    {"generator": "plane", "params": {"size": [8, 8], "subdivisions": 1}, "material": "floor"}
  ],
  "light": {"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.8, 0.8, 0.8]},
  "camera": {"position": [0, 0.95, 3.2], "look_at": [0, 0.46, 0], "fov_deg": 30, "width": 640, "height": 480},
  "environment": {"procedural": "checker"}
})";

// A glass cube rotated 45 degrees about X and about Y, seen along the grid's diagonal (1, 1, 1): its edges
// and corners cut voxels at their corners, where a fixed step slips past.
constexpr std::string_view kCornerScene = R"({
  "materials": [
    {"name": "glass", "kind": "dielectric", "ior": 1.5, "absorption": [0.2, 0.1, 0.05]},
    {"name": "floor", "kind": "opaque", "color": [0.6, 0.58, 0.55]}
  ],
  "meshes": [
    {"generator": "box", "params": {"lo": [-0.5, -0.5, -0.5], "hi": [0.5, 0.5, 0.5]}, "material": "glass",
     "transform": {"rotate_deg": [45, 45, 0], "translate": [0, 1.0, 0]}},
    {"generator": "plane", "params": {"size": [6, 6], "subdivisions": 1}, "material": "floor"}
  ],
  "light": {"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.8, 0.8, 0.8]},
  "camera": {"position": [2.2, 3.2, 2.2], "look_at": [0, 1.0, 0], "fov_deg": 40, "width": 640, "height": 480},
  "environment": {"procedural": "checker"}
})";

// data/scenes/ball-figure.json: a glass ball holding an opaque torus and an amber glass sphere.
constexpr std::string_view kBallFigureScene = R"({
  "materials": [
    {"name": "glass", "kind": "dielectric", "ior": 1.5, "absorption": [0.05, 0.05, 0.05]},
    {"name": "amber", "kind": "dielectric", "ior": 1.6, "absorption": [0.3, 1.5, 4.0]},
    {"name": "red", "kind": "opaque", "color": [0.85, 0.15, 0.1]},
    {"name": "floor", "kind": "opaque", "color": [0.6, 0.58, 0.55]}
  ],
  "meshes": [
    {"generator": "sphere", "params": {"radius": 1.0, "stacks": 48, "slices": 96}, "material": "glass",
     "transform": {"translate": [0, 1.05, 0]}},
    {"generator": "torus", "params": {"major": 0.45, "minor": 0.14, "rings": 32, "sides": 16},
     "material": "red", "transform": {"rotate_deg": [70, 20, 0], "translate": [-0.1, 1.05, -0.1]}},
    {"generator": "sphere", "params": {"radius": 0.22, "stacks": 16, "slices": 32}, "material": "amber",
     "transform": {"translate": [0.35, 1.35, 0.3]}},
    {"generator": "plane", "params": {"size": [8, 8], "subdivisions": 1}, "material": "floor"}
  ],
  "light": {"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.8, 0.8, 0.8]},
  "camera": {"position": [0, 1.6, 4.8], "look_at": [0, 1.0, 0], "fov_deg": 40, "width": 640, "height": 480},
  "environment": {"procedural": "checker"}
})";

// Two glass blocks of different index (1.5 and 1.8) 0.002 apart, far under a voxel: their boundary voxels
// hold both materials. Not quite touching, as first measured (when the reference skipped 1e-4 of the
// scene's size after every surface and so crossed coincident faces as a film of air; it now takes them as
// one glass-flint interface, reference_scene.h).
constexpr std::string_view kTouchingScene = R"({
  "materials": [
    {"name": "glass", "kind": "dielectric", "ior": 1.5, "absorption": [0.1, 0.1, 0.1]},
    {"name": "flint", "kind": "dielectric", "ior": 1.8, "absorption": [0.4, 0.2, 0.05]},
    {"name": "floor", "kind": "opaque", "color": [0.6, 0.58, 0.55]}
  ],
  "meshes": [
    {"generator": "box", "params": {"lo": [-0.7, 0.3, -0.5], "hi": [0, 1.3, 0.5]}, "material": "glass",
     "transform": {"rotate_deg": [0, 25, 0]}},
    {"generator": "box", "params": {"lo": [0.002, 0.3, -0.5], "hi": [0.702, 1.3, 0.5]}, "material": "flint",
     "transform": {"rotate_deg": [0, 25, 0]}},
    {"generator": "plane", "params": {"size": [8, 8], "subdivisions": 1}, "material": "floor"}
  ],
  "light": {"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.8, 0.8, 0.8]},
  "camera": {"position": [0.4, 1.9, 3.6], "look_at": [0, 0.8, 0], "fov_deg": 40, "width": 640, "height": 480},
  "environment": {"procedural": "checker"}
})";

// The thin-wall family (issue 19 item 3): thin-vase-floor.json's vase (1.4 high, so the fitted refraction
// grid's voxel is 1.4 / (res - 2 x VoxelRefraction::kFineMarginVoxels)) with a wall `voxels` of those voxels
// thick, standing on an 8 x 8 floor, an opaque box inside it and a torus behind it, under a constant sky.
constexpr float kThinWallHeight = 1.4f;
constexpr double kThinWallVoxels[] = {0.5, 1.0, 2.0, 4.0, 8.0};

std::string thin_wall_scene(double voxels, uint32_t resolution) {
  const double voxel = kThinWallHeight / (double(resolution) - 2.0 * VoxelRefraction::kFineMarginVoxels);
  return fmt::format(R"({{
  "materials": [
    {{"name": "glass", "kind": "dielectric", "ior": 1.5, "absorption": [0.3, 0.1, 0.2]}},
    {{"name": "floor", "kind": "opaque", "color": [0.6, 0.58, 0.55]}},
    {{"name": "box", "kind": "opaque", "color": [0.8, 0.25, 0.2]}},
    {{"name": "torus", "kind": "opaque", "color": [0.2, 0.45, 0.8]}}
  ],
  "meshes": [
    {{"generator": "vase", "params": {{"height": {}, "thickness": {}, "segments": 96, "rows": 64,
                                     "profile": [0.42, 0.56, 0.6, 0.5, 0.34, 0.3, 0.36]}},
     "material": "glass"}},
    {{"generator": "box", "params": {{"lo": [-0.15, 0.06, -0.15], "hi": [0.15, 0.5, 0.15]}}, "material": "box"}},
    {{"generator": "torus", "params": {{"major": 0.45, "minor": 0.12}},
     "material": "torus", "transform": {{"rotate_deg": [90, 0, 0], "translate": [0.3, 0.6, -1.4]}}}},
    {{"generator": "plane", "params": {{"size": [8, 8], "subdivisions": 1}}, "material": "floor"}}
  ],
  "light": {{"type": "directional", "direction": [-0.4, -1, -0.5], "intensity": [0.8, 0.8, 0.8]}},
  "camera": {{"position": [0, 2.2, 3.8], "look_at": [0, 0.7, 0], "fov_deg": 40, "width": 640, "height": 480}},
  "environment": {{"color": [0.7, 0.75, 0.8]}}
}})",
                     kThinWallHeight, voxels * voxel);
}

// ---- Pictures ----

// `image` shrunk by an integer factor (box filter) so that it is at most `max_width` wide.
ImageRgba shrink(const ImageRgba& image, uint32_t max_width) {
  const uint32_t f = std::max(1u, (image.width + max_width - 1) / max_width);
  ImageRgba out(image.width / f, image.height / f);
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      glm::vec4 sum(0.0f);
      for (uint32_t dy = 0; dy < f; ++dy)
        for (uint32_t dx = 0; dx < f; ++dx) sum += image.at(x * f + dx, y * f + dy);
      out.at(x, y) = sum / float(f * f);
    }
  return out;
}

// One row per method of three tiles: the method's image, the reference's, their difference (error_image:
// the shadows' transmittance at full scale 1, the refraction images' at 0.25).
class Picture {
 public:
  void add(const ImageRgba& method, const ImageRgba& reference, const ImageRgba& difference) {
    rows_.push_back({shrink(method, kTile), shrink(reference, kTile), shrink(difference, kTile)});
  }

  // Writes the picture as `dir`/rendering-`name`.png ('/' in the name becomes '-') and returns the path
  // relative to `dir`; nothing (empty) when `dir` is empty or there are no rows.
  std::string write(const std::filesystem::path& dir, const std::string& name) const {
    if (dir.empty() || rows_.empty()) return {};
    std::string file = "rendering-" + name + ".png";
    std::replace(file.begin(), file.end(), '/', '-');
    const uint32_t w = rows_[0][0].width, h = rows_[0][0].height;
    ImageRgba out(3 * w + 2 * kGap, uint32_t(rows_.size()) * (h + kGap) - kGap, glm::vec4(1.0f));
    for (size_t r = 0; r < rows_.size(); ++r)
      for (uint32_t t = 0; t < 3; ++t)
        for (uint32_t y = 0; y < h; ++y)
          for (uint32_t x = 0; x < w; ++x)
            out.at(t * (w + kGap) + x, uint32_t(r) * (h + kGap) + y) =
                glm::vec4(glm::vec3(rows_[r][t].at(x, y)), 1.0f);
    write_image(out, dir / file);
    return file;
  }

 private:
  static constexpr uint32_t kTile = 160, kGap = 4;
  std::vector<std::array<ImageRgba, 3>> rows_;
};

void set_picture(std::vector<StabilityRow>& rows, const std::string& file) {
  for (StabilityRow& r : rows) r.picture = file;
}

// ---- Shadows ----

struct ShadowCase {
  std::string label;  // voxel-center, voxel-conservative, uniform, filter, opaque, voxel-exact
  ShadowMethod method;
  RasterMode mode;
};

// Every device shadow method of kShadowMethods (the voxel one in both raster modes).
std::vector<ShadowCase> shadow_methods() {
  std::vector<ShadowCase> out;
  for (const ShadowMethodInfo& info : kShadowMethods) {
    if (info.value == ShadowMethod::kReference || info.value == ShadowMethod::kNone) continue;
    if (info.value == ShadowMethod::kVoxel) {
      out.push_back({"voxel-center", info.value, RasterMode::kCenter});
      out.push_back({"voxel-conservative", info.value, RasterMode::kConservative});
    } else {
      out.push_back({std::string(info.name), info.value, RasterMode::kCenter});
    }
  }
  return out;
}

// What the sheet case measures besides the transmittance RMSE over every receiver.
enum class SheetMeasures { kNone, kAcneAndLeaks };

// Every shadow method on `s`: transmittance RMSE over the visible receivers against Embree's exact
// transmittance at the same samples, non-finite pixels (image or transmittance; must be 0), and for the
// sheet case acne (transmittance RMSE over the receivers on the lit leaf, exactly lit there) and leaks (the
// mean transmittance, largest channel, of floor receivers the exact shadow leaves fully dark).
// `required_rmse`: the RMSE rows' bound is this requirement, for `required_reason` (voxel-exact's own where
// tighter), not kBounds'.
std::vector<StabilityRow> run_shadow_case(StabilityContext& ctx, const std::string& name, RenderCase& s,
                                          SheetMeasures sheet, std::optional<double> required_rmse = {},
                                          const std::string& required_reason = {}) {
  const Version v = version(ctx.full);
  FrameRenderer renderer(ctx.cl);
  renderer.set_scene(s.soup(), s.materials());
  RenderedFrame primary;
  ReferenceFrame reference;
  reference.shadows = case_exact_shadows(renderer, s, &primary);
  const std::vector<glm::vec3>& exact = reference.shadows->transmittance;
  const std::vector<uint8_t>& mask = reference.shadows->receivers;
  const uint64_t receivers = uint64_t(std::count(mask.begin(), mask.end(), uint8_t(1)));
  if (receivers == 0) fail("rendering_stability.cpp: case {} has no visible receiver", name);
  // The sheet case's two regions.
  std::vector<uint8_t> leaf(mask.size(), 0), dark(mask.size(), 0);
  if (sheet == SheetMeasures::kAcneAndLeaks) {
    for (size_t i = 0; i < mask.size(); ++i) {
      const uint32_t m = primary.samples[i].material;
      leaf[i] = mask[i] && s.materials()[m].kind == MaterialKind::kSheet;
      const float e = std::max(exact[i].x, std::max(exact[i].y, exact[i].z));
      dark[i] = mask[i] && s.materials()[m].kind == MaterialKind::kOpaque && e == 0.0f;
    }
    if (std::count(leaf.begin(), leaf.end(), uint8_t(1)) == 0 ||
        std::count(dark.begin(), dark.end(), uint8_t(1)) == 0)
      fail("rendering_stability.cpp: case {} shows no lit leaf or no fully shadowed floor", name);
  }

  // The purpose baseline: no shadow at all (transmittance 1) at the same receivers.
  const std::vector<glm::vec3> unshadowed(exact.size(), glm::vec3(1.0f));
  const double no_shadow = transmittance_error(unshadowed, exact, mask, 0.05).rmse;
  const std::pair<double, std::string> shadow_baseline{
      no_shadow,
      fmt::format("purpose: below no shadow's transmittance RMSE ({:.4g}) at the same receivers", no_shadow)};
  std::vector<StabilityRow> rows;
  Picture picture;
  for (const ShadowCase& m : shadow_methods()) {
    RenderOptions o;
    o.shadows = m.method;
    o.mode = m.mode;
    o.shadow_resolution = v.shadow_resolution;
    o.keep_samples = true;
    renderer.prepare(o);
    const RenderedFrame frame = renderer.render(s.light(), s.camera(), o);
    const TransmittanceError e = measure_against_reference(frame, reference).shadows->transmittance;
    const std::string measure = "transmittance RMSE over visible receivers";
    std::string note =
        fmt::format("{} receivers, {:.1f}% off by > 0.05", e.receivers, 100.0 * e.share_over_threshold);
    if (required_rmse) {
      const bool exact = m.method == ShadowMethod::kVoxelExact;
      const double bound = exact ? std::min(*required_rmse, kVoxelExactShadowRmse) : *required_rmse;
      rows.push_back(
          row(name, m.label, measure, e.rmse, bound, false, note,
              exact && bound < *required_rmse ? std::string(kExactShadowTarget) : required_reason));
    } else {
      rows.push_back(measured_row(name, m.label, measure, Measure::kShadowRmse, e.rmse, ctx.full, note, false,
                                  shadow_baseline));
    }
    uint64_t nonfinite = 0;
    for (size_t i = 0; i < frame.image.pixels.size(); ++i)
      nonfinite += !finite(glm::vec3(frame.image.pixels[i])) || !finite(frame.transmittance[i]);
    rows.push_back(row(name, m.label, "non-finite pixels", double(nonfinite), 0.0, false,
                       "image or transmittance NaN or infinite",
                       "physics: radiance and transmittance are finite"));
    if (sheet == SheetMeasures::kAcneAndLeaks) {
      const TransmittanceError acne = transmittance_error(frame.transmittance, exact, leaf, 0.05);
      rows.push_back(measured_row(name, m.label, "acne: transmittance RMSE on the lit leaf", Measure::kAcne,
                                  acne.rmse, ctx.full,
                                  fmt::format("{} leaf receivers, {:.1f}% darkened by > 0.05", acne.receivers,
                                              100.0 * acne.share_over_threshold)));
      double leaked = 0.0;
      uint64_t count = 0;
      for (size_t i = 0; i < dark.size(); ++i)
        if (dark[i]) {
          const glm::vec3 t = frame.transmittance[i];
          leaked += std::max(t.x, std::max(t.y, t.z));
          ++count;
        }
      rows.push_back(measured_row(name, m.label, "leak: mean transmittance under the closed slab",
                                  Measure::kLeak, leaked / double(count), ctx.full,
                                  fmt::format("{} floor receivers exactly in the slab's shadow", count)));
    }
    picture.add(frame.image, reference.shadows->image,
                error_image(frame.transmittance, exact, v.width, v.height, mask, 1.0));
  }
  set_picture(rows, picture.write(ctx.picture_dir, name));
  return rows;
}

// The light travelling at `degrees` from the receiver plane's normal (+y), along +x.
std::function<void(Scene&)> light_from_normal(double degrees) {
  return [degrees](Scene& scene) {
    const double r = degrees * std::numbers::pi / 180.0;
    scene.light.direction = glm::vec3(float(std::sin(r)), float(-std::cos(r)), 0.0f);
  };
}

// Throws voxr::Error when kBounds lacks a row of `measures` for one of `methods` on case `name`: a method
// added without its bounds is an error when the suite is built, not a silent default.
void require_bounds(const std::string& name, const std::vector<std::string>& methods,
                    std::initializer_list<Measure> measures) {
  for (const std::string& method : methods)
    for (Measure m : measures)
      if (!find_bound(name, method, m))
        fail("rendering stability case {}: method {} has no bound for measure {} (kBounds)", name, method,
             std::array{"shadow RMSE", "acne", "leak", "image RMSE", "event mismatch", "TIR found"}[int(m)]);
}

StabilityCase shadow_case(std::string name, std::string description, std::string_view json,
                          std::function<void(Scene&)> edit = {}, SheetMeasures sheet = SheetMeasures::kNone,
                          std::optional<double> required_rmse = {}, std::string required_reason = {}) {
  std::vector<std::string> labels;
  for (const ShadowCase& m : shadow_methods()) labels.push_back(m.label);
  // voxel-exact is held to its target everywhere (kExactShadowTarget), the others to no shadow's RMSE.
  if (!required_rmse) require_bounds(name, {"voxel-exact"}, {Measure::kShadowRmse});
  if (sheet == SheetMeasures::kAcneAndLeaks) require_bounds(name, labels, {Measure::kAcne, Measure::kLeak});
  StabilityCase c;
  c.family = kFamily;
  c.name = name;
  c.description = std::move(description);
  c.run = [name, json, edit, sheet, required_rmse, required_reason](StabilityContext& ctx) {
    return run_shadow_case(ctx, name, *make_scene(name, json, version(ctx.full), edit), sheet, required_rmse,
                           required_reason);
  };
  return c;
}

// The light `degrees` above the receiver plane (y = 0), its horizontal part along (1, 0, 0.3): across the
// light grid's columns, obliquely.
std::function<void(Scene&)> light_above_horizon(double degrees) {
  return [degrees](Scene& scene) {
    const double r = degrees * std::numbers::pi / 180.0, h = std::cos(r) / std::sqrt(1.09);
    scene.light.direction = glm::vec3(float(h), float(-std::sin(r)), float(0.3 * h));
  };
}

// ---- Refraction ----

// Every device refraction method of kRefractionMethods, with its defaults.
std::vector<RefractionMethodInfo> refraction_methods() {
  std::vector<RefractionMethodInfo> out;
  for (const RefractionMethodInfo& info : kRefractionMethods)
    if (!is_reference_refraction(info.value) && info.value != RefractionMethod::kNone) out.push_back(info);
  return out;
}

uint64_t tir_pixels(std::span<const RefractionPath> paths) {
  return uint64_t(std::count_if(paths.begin(), paths.end(),
                                [](const RefractionPath& p) { return p.events & VOXR_PATH_TIR; }));
}

// Every refraction method on `s`, each frame with the exact shadows at its path ends: image RMSE and event
// mismatch share against the matched reference, non-finite pixels (must be 0); with `tir`, whether the
// reference has total internal reflection (hard: at least one pixel) and the share of the reference's TIR
// pixels where the method's path reflects totally too.
std::vector<StabilityRow> run_refraction_case(StabilityContext& ctx, const std::string& name, RenderCase& s,
                                              bool tir, RefractionGrid grid) {
  const Version v = version(ctx.full);
  ReferenceFrame reference;
  reference.refraction = render_refraction_reference(s.reference().scene(), s.render_materials(), s.light(),
                                                     s.environment(), s.camera(), ReferenceModel::kMatched);
  const RefractionReference& exact = *reference.refraction;
  std::vector<StabilityRow> rows;
  const uint64_t reference_tir = tir_pixels(exact.paths);
  if (tir)
    rows.push_back(row(name, "reference", "pixels with total internal reflection", double(reference_tir), 1.0,
                       true, "the matched reference's paths: the scene shows TIR",
                       "physics: rays inside IOR 2.42 beyond 24.4 degrees reflect totally"));
  FrameRenderer renderer(ctx.cl);
  renderer.set_scene(s.soup(), s.materials(), &s.reference());
  renderer.set_environment(s.environment());
  // The purpose baseline: the glass drawn unrefracted (--refraction none) with the same exact shadows.
  RenderOptions unrefracted;
  unrefracted.shadows = ShadowMethod::kReference;
  unrefracted.refraction.method = RefractionMethod::kNone;
  renderer.prepare(unrefracted);
  const double none_rmse = rmse(renderer.render(s.light(), s.camera(), unrefracted).image, exact.image);
  const std::pair<double, std::string> image_baseline{
      none_rmse, fmt::format("purpose: below the image RMSE of the glass unrefracted ({:.4g})", none_rmse)};
  Picture picture;
  for (const RefractionMethodInfo& m : refraction_methods()) {
    const std::string method(m.name);
    RenderOptions o;
    o.shadows = ShadowMethod::kReference;
    o.refraction.method = m.value;
    o.refraction.resolution = v.refraction_resolution;
    o.refraction.grid = grid;
    o.keep_samples = true;
    RenderedFrame frame;
    try {
      renderer.prepare(o);
      frame = renderer.render(s.light(), s.camera(), o);
    } catch (const Error& e) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      rows.push_back(row(name, method, "image RMSE vs matched reference", nan, 0.0, false, e.what(),
                         "rule: every method renders every case"));
      continue;
    }
    const RefractionError e = *measure_against_reference(frame, reference).refraction;
    rows.push_back(measured_row(name, method, "image RMSE vs matched reference", Measure::kImageRmse, e.rmse,
                                ctx.full, fmt::format("PSNR {:.1f} dB", e.psnr), false, image_baseline));
    rows.push_back(measured_row(
        name, method, "event mismatch share of refracted pixels", Measure::kEventMismatch,
        e.event_mismatch_share, ctx.full,
        fmt::format(
            "{} refracted pixels, {} lost by the reference (not compared), {} by the method (differing)",
            e.refracted_pixels, e.lost_pixels, e.method_lost_pixels)));
    rows.push_back(row(name, method, "non-finite pixels", double(e.nonfinite_pixels), 0.0, false,
                       "image NaN or infinite", "physics: radiance is finite"));
    if (tir) {
      uint64_t both = 0;
      for (size_t i = 0; i < exact.paths.size(); ++i)
        both += (exact.paths[i].events & VOXR_PATH_TIR) && (frame.paths[i].events & VOXR_PATH_TIR);
      const double found = reference_tir ? double(both) / double(reference_tir) : 0.0;
      rows.push_back(measured_row(name, method, "TIR found: share of the reference's TIR pixels",
                                  Measure::kTirFound, found, ctx.full,
                                  fmt::format("{} of {}; the method has TIR at {} pixels", both,
                                              reference_tir, tir_pixels(frame.paths)),
                                  true));
    }
    picture.add(frame.image, exact.image, error_image(frame.image, exact.image, 0.25));
  }
  set_picture(rows, picture.write(ctx.picture_dir, name));
  return rows;
}

// The cases measured before the fitted grid run on the whole scene's grid, as their bounds were measured.
// The refraction methods' names, and the bounds every refraction case needs from kBounds.
void require_refraction_bounds(const std::string& name, bool tir) {
  std::vector<std::string> methods;
  for (const RefractionMethodInfo& m : refraction_methods()) methods.emplace_back(m.name);
  require_bounds(name, methods, {Measure::kEventMismatch});
  require_bounds(name, {"voxel-exact"}, {Measure::kImageRmse});
  if (tir) require_bounds(name, methods, {Measure::kTirFound});
}

StabilityCase refraction_case(std::string name, std::string description, std::string_view json,
                              bool tir = false) {
  require_refraction_bounds(name, tir);
  StabilityCase c;
  c.family = kFamily;
  c.name = name;
  c.description = std::move(description);
  c.run = [name, json, tir](StabilityContext& ctx) {
    return run_refraction_case(ctx, name, *make_scene(name, json, version(ctx.full)), tir,
                               RefractionGrid::kScene);
  };
  return c;
}

StabilityCase thin_wall_case(double voxels) {
  StabilityCase c;
  c.family = kFamily;
  c.name = fmt::format("thin-wall/{:g}", voxels);
  require_refraction_bounds(c.name, false);
  c.description = fmt::format(
      "A glass vase whose wall is {:g} voxels of the fitted refraction grid thick, standing on a floor with "
      "an opaque box inside and a torus behind (thin-vase-floor.json): under 1 voxel the wall's two surfaces "
      "share boundary voxels and their normals cancel, from about 4 the surfaces have runs of their own",
      voxels);
  c.run = [name = c.name, voxels](StabilityContext& ctx) {
    const Version v = version(ctx.full);
    const std::string json = thin_wall_scene(voxels, v.refraction_resolution);
    return run_refraction_case(ctx, name, *make_scene(name, json, v), false, RefractionGrid::kFitted);
  };
  return c;
}

}  // namespace

std::vector<StabilityCase> rendering_stability_cases() {
  std::vector<StabilityCase> cases;
  for (int degrees : {80, 85, 88})
    cases.push_back(shadow_case(
        fmt::format("grazing-light/{}", degrees),
        fmt::format("Light {} degrees from the receiver plane's normal: long shadows cross many light-grid "
                    "columns per receiver and self-shadow acne grows with the slope (DESIGN.md: grazing "
                    "angles)",
                    degrees),
        kGrazingScene, light_from_normal(degrees)));
  for (int degrees : {1, 2, 3})
    cases.push_back(shadow_case(
        fmt::format("grazing-floor/{}", degrees),
        fmt::format(
            "A lone floor under a directional light {} degrees above the horizon (issue 20): its own "
            "crossing lies many slabs deeper in the neighbouring light-grid columns, so a lookup at the "
            "receiver's depth shadowed it; a plane cannot shadow itself (requirement: RMSE <= {})",
            degrees, kGrazingFloorRmse),
        kLoneFloorScene, light_above_horizon(degrees), SheetMeasures::kNone, kGrazingFloorRmse,
        "issue 20 target: a plane is no caster of itself (transmittance exactly 1), RMSE <= 0.02"));
  cases.push_back(shadow_case(
      "grazing-floor-box/3",
      fmt::format(
          "The lone floor with a box on it, light 3 degrees above the horizon: the floor must stay lit "
          "and the box's long shadow must stay (requirement: RMSE <= {})",
          kFloorBoxRmse),
      kFloorBoxScene, light_above_horizon(3), SheetMeasures::kNone, kFloorBoxRmse,
      "rule: the floor stays lit and the box's shadow stays (no shadow measures >= 0.25, the floor shadowing "
      "itself 0.31); the shadow's long edges blur over one light-grid column (0.04)"));
  cases.push_back(shadow_case(
      "far-point-light",
      fmt::format(
          "A sphere over a floor under a point light 1e5 units up (issue 20): a frustum's slabs uniform "
          "in 1/depth fall below float resolution and lost the shadow; the light is taken as parallel "
          "(requirement: RMSE <= {})",
          kFarPointLightRmse),
      kFarPointLightScene, {}, SheetMeasures::kNone, kFarPointLightRmse,
      "issue 20 target: a point light 1e5 units up keeps the sphere's shadow, RMSE <= 0.05"));
  cases.push_back(shadow_case(
      "grazing-view",
      "Camera 2.5 degrees above the receiver plane: one pixel spans a long stretch of floor, so the "
      "light grid's coarseness shows along the view",
      kGrazingScene, [](Scene& scene) {
        scene.camera.position = glm::vec3(0.0f, 0.15f, 3.4f);
        scene.camera.look_at = glm::vec3(0.0f, 0.0f, 0.0f);
      }));
  cases.push_back(shadow_case(
      "receivers-among-casters",
      "Receivers inside a block of leaves with opaque objects among them (foliage.json): each receiver's own "
      "voxels and its neighbours' darken it, where a bias against acne lets light leak",
      kFoliageScene));
  cases.push_back(shadow_case(
      "sheet-self-shadowing",
      "A lit leaf darkened by its own voxels (acne) and light through a closed opaque slab 0.04 thick, under "
      "one light-grid voxel in the small version (leaks): the two failures a shadow bias trades",
      kSheetScene, {}, SheetMeasures::kAcneAndLeaks));
  cases.push_back(refraction_case(
      "total-internal-reflection",
      "A faceted gem of IOR 2.42 (gem.json): most rays that enter reflect totally inside before "
      "they leave; a method must find the reflection and follow the mirrored ray",
      kGemScene, true));
  cases.push_back(refraction_case("nested-thin-shells",
                                  "A glass shell 0.03 thick (thin-shell.json): both walls' boundaries share "
                                  "voxels along one ray, where a voxel march loses or merges interfaces "
                                  "(Chang & Lai PG 2011's angle threshold)",
                                  kThinShellScene));
  cases.push_back(refraction_case(
      "grazing-slab",
      "A glass slab seen 8 degrees from its plane: rays run along its faces through long runs of boundary "
      "voxels",
      kGrazingSlabScene));
  cases.push_back(refraction_case(
      "voxel-corners",
      "A glass cube rotated 45 degrees about two axes seen along the grid's diagonal: rays slip between "
      "voxels that touch only at corners when the march steps a whole voxel (the papers' fixed step)",
      kCornerScene));
  cases.push_back(refraction_case("multi-material/ball-figure",
                                  "A glass ball holding an opaque torus and an amber glass sphere "
                                  "(ball-figure.json, after Chang & Lai PG 2011): "
                                  "several materials on one path",
                                  kBallFigureScene));
  cases.push_back(refraction_case("multi-material/touching",
                                  "Two glass blocks of index 1.5 and 1.8 side by side, 0.002 apart: the ray "
                                  "passes from one dielectric into the other within one voxel, whose "
                                  "boundary voxels hold both materials",
                                  kTouchingScene));
  for (double voxels : kThinWallVoxels) cases.push_back(thin_wall_case(voxels));
  return cases;
}

}  // namespace voxr
