// The photometric readers (core/light/photometry.h) against the sixteen real files in
// ../shared/photometry (flux figures from its README, produced independently by summarize.py),
// closed forms (Lambertian pi I0, isotropic 4 pi I0), the symmetry rules, and every class of
// malformed file (table-driven over mutated copies of real files).
#include "core/light/photometry.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.h"

namespace ilp {
namespace {

constexpr double kPi = std::numbers::pi;
const std::string kShared = std::string(ILP_SOURCE_DIR) + "/../shared/photometry/";

std::string shared_file(const std::string& name) { return kShared + name; }
std::string shared_text(const std::string& name) { return test::read_file(shared_file(name)); }

struct RealFile {
  std::string name;
  double flux_trap_lm;   // README "flux trap (lm)"
  double lamp_flux_lm;   // README stated lamps x lm / lamp set 1 (absolute: 0 = use the integral)
  double watts;
  double upward_percent; // README "up %" (IES) or 100 - integrated DFF (EULUMDAT)
};

// The two README tables (python3 summarize.py in ../shared/photometry).
const std::vector<RealFile> kRealFiles = {
    {"lidrs/iesna2002_example_typec.ies", 83640.0, 50000, 495, 0.0},
    {"luxcore/ASA_15M_R2.ies", 9559.0, 13000, 185, 0.0},
    {"radiance/examp1.ies", 5294.3, 5800, 63.7, 69.2},
    {"renderpipeline/area_light.ies", 28297.9, 41000, 433.62, 0.1},
    {"renderpipeline/bollard.ies", 2556.4, 9000, 100, 4.9},
    {"renderpipeline/defined_diffuse.ies", 1294.0, 2200, 100, 0.0},
    {"renderpipeline/medium_scatter.ies", 707.2, 1615, 24, 0.0},
    {"renderpipeline/overhead.ies", 36901.1, 40000, 432, 0.0},
    {"renderpipeline/star_focused.ies", 32.8, 68, 5.4, 0.0},
    {"eulumdat-analysis/sample_01.ldt", 2111.2, 2112, 22.3, 100 - 100.0},
    {"eulumdat-analysis/sample_03.ldt", 1982.1, 1983, 17.6, 100 - 87.0},
    {"eulumdat-analysis/sample_14.ldt", 13707.1, 13729, 93.2, 100 - 52.1},
    {"eulumdat-analysis/sample_17.ldt", 611.8, 0, 6.9, 100 - 100.0},
    {"eulumdat-analysis/sample_18.ldt", 2445.2, 2445.4, 20.178, 100 - 100.0},
    {"eulumdat-analysis/sample_20.ldt", 9999.2, 10002, 75, 100 - 90.4},
    {"lidrs/example.ldt", 5124.3, 5134, 60.22, 100 - 58.0},
};

TEST(PhotometryRealFiles, FluxMatchesTheReadmeWithinHalfAPercent) {
  // The table docs/photometry.md shows (printed so that the figures can be reproduced).
  std::printf("| file | integrated flux (lm) | README trap (lm) | error %% | up %% | symmetry | opening |\n");
  for (const RealFile& f : kRealFiles) {
    SCOPED_TRACE(f.name);
    const Photometry p = load_photometry(shared_file(f.name));
    const double rel = p.luminaire_flux_lm / f.flux_trap_lm - 1;
    static const char* const kSymmetry[] = {"rotational", "quadrant", "bilateral C0-C180", "bilateral C90-C270", "none"};
    static const char* const kShape[] = {"point", "rectangle", "disc", "cylinder"};
    std::printf("| %s | %.2f | %.1f | %+.4f | %.2f | %s | %s %.3f x %.3f x %.3f m |\n", f.name.c_str(),
                p.luminaire_flux_lm, f.flux_trap_lm, 100 * rel, 100 * p.upward_fraction,
                kSymmetry[static_cast<int>(p.symmetry)], kShape[static_cast<int>(p.opening.shape)], p.opening.length_m,
                p.opening.width_m, p.opening.height_m);
    EXPECT_LT(std::abs(rel), 0.005) << p.luminaire_flux_lm << " lm vs README " << f.flux_trap_lm;
    // The README rounds to 0.1 lm: the same rule should agree far better than 0.5 %.
    EXPECT_NEAR(p.luminaire_flux_lm, f.flux_trap_lm, 0.06 + 1e-5 * f.flux_trap_lm);
    EXPECT_DOUBLE_EQ(p.luminaire_flux_lm, integrate_flux_lm(p));
    if (f.lamp_flux_lm > 0) {
      EXPECT_NEAR(p.lamp_flux_lm, f.lamp_flux_lm, 1e-9);
      EXPECT_FALSE(p.absolute);
    } else {
      EXPECT_TRUE(p.absolute);
      EXPECT_DOUBLE_EQ(p.lamp_flux_lm, p.luminaire_flux_lm);
    }
    EXPECT_NEAR(p.input_power_w, f.watts, 1e-9);
    EXPECT_NEAR(100 * p.upward_fraction, f.upward_percent, 0.06);
    EXPECT_EQ(p.format, f.name.ends_with(".ies") ? PhotometryFormat::ies : PhotometryFormat::eulumdat);
  }
}

TEST(PhotometryRealFiles, HeaderFieldsAndQuirks) {
  {
    const Photometry p = load_photometry(shared_file("lidrs/iesna2002_example_typec.ies"));
    EXPECT_EQ(p.version, "IESNA: LM-63-2002");
    EXPECT_EQ(p.manufacturer, "Aardvark lighting Inc.");
    EXPECT_EQ(p.catalogue, "SKYVIEW 123-XYZ-abs-400");
    ASSERT_TRUE(p.tilt.has_value());
    EXPECT_EQ(p.tilt->geometry, 1);
    ASSERT_EQ(p.tilt->angles_deg.size(), 13u);
    EXPECT_DOUBLE_EQ(p.tilt->angles_deg[12], 180);
    EXPECT_DOUBLE_EQ(p.tilt->factors[5], 0.87);
    EXPECT_EQ(p.symmetry, PhotometricSymmetry::quadrant);
    // Warnings: tilt not applied; the invented intensities exceed the stated lamp lumens.
    ASSERT_EQ(p.warnings.size(), 2u);
    EXPECT_NE(p.warnings[0].find("TILT=INCLUDE"), std::string::npos);
    EXPECT_NE(p.warnings[1].find("light output ratio"), std::string::npos);
  }
  {
    const Photometry p = load_photometry(shared_file("luxcore/ASA_15M_R2.ies"));  // CRLF
    EXPECT_EQ(p.luminaire, "ASA SERIES 150W PULSE START MH TYPE 2 FULL CUTOFF");
    EXPECT_EQ(p.symmetry, PhotometricSymmetry::bilateral_c0_c180);
    EXPECT_EQ(p.opening.shape, OpeningShape::rectangle);
    EXPECT_NEAR(p.opening.width_m, 1.24 * 0.3048, 1e-12);
    EXPECT_TRUE(p.warnings.empty());
  }
  {
    const Photometry p = load_photometry(shared_file("radiance/examp1.ies"));
    EXPECT_EQ(p.version, "IESNA95");
    EXPECT_EQ(p.manufacturer, "Ledalite Architectural Products  604-888-6811");
    EXPECT_EQ(p.opening.shape, OpeningShape::rectangle);
    EXPECT_NEAR(p.opening.width_m, 0.85 * 0.3048, 1e-12);   // along C90-C270
    EXPECT_NEAR(p.opening.length_m, 4.04 * 0.3048, 1e-12);  // along C0-C180, "0 degree plane parallel to lamps"
    EXPECT_NEAR(p.opening.height_m, 0.292 * 0.3048, 1e-12);
  }
  {
    const Photometry p = load_photometry(shared_file("renderpipeline/bollard.ies"));
    EXPECT_EQ(p.opening.shape, OpeningShape::cylinder);
    EXPECT_NEAR(p.opening.width_m, 0.49 * 0.3048, 1e-12);
    EXPECT_NEAR(p.opening.length_m, 0.49 * 0.3048, 1e-12);
    EXPECT_NEAR(p.opening.height_m, 0.406 * 0.3048, 1e-12);
    EXPECT_EQ(p.symmetry, PhotometricSymmetry::rotational);
  }
  {
    const Photometry p = load_photometry(shared_file("renderpipeline/defined_diffuse.ies"));  // 1986, END, ^Z
    EXPECT_EQ(p.version, "");
    EXPECT_EQ(p.luminaire, "ERCO Leuchten GmbH");
    EXPECT_EQ(p.opening.shape, OpeningShape::point);
    EXPECT_TRUE(p.warnings.empty());
  }
  {
    const Photometry p = load_photometry(shared_file("renderpipeline/medium_scatter.ies"));  // metres
    EXPECT_NEAR(p.opening.width_m, 0.103, 1e-12);
    EXPECT_NEAR(p.opening.length_m, 0.059, 1e-12);
  }
  {
    const Photometry p = load_photometry(shared_file("eulumdat-analysis/sample_17.ldt"));  // BOM, absolute
    EXPECT_EQ(p.manufacturer, "ERCO GmbH");
    EXPECT_EQ(p.luminaire, "Iku Surface-mounted downlight");
    EXPECT_EQ(p.catalogue, "B0000178_V01");
    EXPECT_TRUE(p.absolute);
    ASSERT_EQ(p.lamp_sets.size(), 1u);
    EXPECT_EQ(p.lamp_sets[0].count, -1);
    EXPECT_DOUBLE_EQ(p.lamp_sets[0].flux_lm, 611.9);
    EXPECT_EQ(p.opening.shape, OpeningShape::disc);
    EXPECT_NEAR(p.opening.length_m, 0.076, 1e-12);
    EXPECT_NEAR(p.opening.width_m, 0.076, 1e-12);
    EXPECT_EQ(p.symmetry, PhotometricSymmetry::rotational);
  }
  {
    const Photometry p = load_photometry(shared_file("eulumdat-analysis/sample_03.ldt"));  // two lamp sets
    ASSERT_EQ(p.lamp_sets.size(), 2u);
    EXPECT_DOUBLE_EQ(p.lamp_sets[1].flux_lm, 2643);
    EXPECT_DOUBLE_EQ(p.lamp_sets[1].power_w, 24.9);
    EXPECT_EQ(p.lamp_sets[1].colour, "nw");
    EXPECT_DOUBLE_EQ(p.lamp_flux_lm, 1983);
    EXPECT_EQ(p.symmetry, PhotometricSymmetry::quadrant);
    EXPECT_EQ(p.opening.shape, OpeningShape::rectangle);
    EXPECT_NEAR(p.opening.length_m, 1.208, 1e-12);
    EXPECT_NEAR(p.opening.width_m, 0.105, 1e-12);
    EXPECT_NEAR(p.opening.height_m, 0.051, 1e-12);
    EXPECT_TRUE(p.warnings.empty());
  }
  {
    const Photometry p = load_photometry(shared_file("eulumdat-analysis/sample_14.ldt"));  // round luminaire
    EXPECT_EQ(p.opening.shape, OpeningShape::disc);
    EXPECT_NEAR(p.opening.width_m, 0.662, 1e-12);
    EXPECT_EQ(p.symmetry, PhotometricSymmetry::none);
  }
  {
    const Photometry p = load_photometry(shared_file("eulumdat-analysis/sample_18.ldt"));
    EXPECT_EQ(p.c_angles_deg.size(), 361u);
    EXPECT_EQ(p.gamma_angles_deg.size(), 181u);
    EXPECT_EQ(p.opening.shape, OpeningShape::rectangle);  // luminous area 100 x 100 mm
  }
  {
    const Photometry p = load_photometry(shared_file("eulumdat-analysis/sample_20.ldt"));  // Dg = 0
    ASSERT_EQ(p.gamma_angles_deg.size(), 55u);
    EXPECT_TRUE(p.warnings.empty());
  }
}

// The three products shipped in data/photometry, with the figures of its README.
TEST(PhotometryShippedProducts, FluxAsDocumented) {
  const std::string data = std::string(ILP_SOURCE_DIR) + "/data/photometry/";
  struct Product {
    std::string file;
    double flux_lm, lamp_flux_lm, power_w, up_percent;
    OpeningShape shape;
  };
  for (const Product& pr : {Product{"erco_iku_downlight.ldt", 611.8, 611.8, 6.9, 0, OpeningShape::disc},
                            Product{"linear_led_2112lm.ldt", 2111.2, 2112, 22.3, 0, OpeningShape::rectangle},
                            Product{"ledalite_direct_indirect.ies", 5294.3, 5800, 63.7, 69.2, OpeningShape::rectangle}}) {
    SCOPED_TRACE(pr.file);
    const Photometry p = load_photometry(data + pr.file);
    EXPECT_NEAR(p.luminaire_flux_lm, pr.flux_lm, 0.05);
    EXPECT_NEAR(p.lamp_flux_lm, pr.lamp_flux_lm, 0.05);
    EXPECT_NEAR(p.input_power_w, pr.power_w, 1e-9);
    EXPECT_NEAR(100 * p.upward_fraction, pr.up_percent, 0.05);
    EXPECT_EQ(p.opening.shape, pr.shape);
    EXPECT_TRUE(p.warnings.empty());
    // Byte for byte the shared file.
    const std::string shared = pr.file == "erco_iku_downlight.ldt"  ? "eulumdat-analysis/sample_17.ldt"
                               : pr.file == "linear_led_2112lm.ldt" ? "eulumdat-analysis/sample_01.ldt"
                                                                    : "radiance/examp1.ies";
    EXPECT_EQ(test::read_file(data + pr.file), shared_text(shared));
  }
}

TEST(PhotometryRealFiles, HeaderThatDisagreesWithTheDataWarns) {
  const Photometry p = load_photometry(shared_file("lidrs/example.ldt"));
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_NE(p.warnings[0].find("field 22 DFF states 100 % downward"), std::string::npos) << p.warnings[0];
  EXPECT_NEAR(p.stated_dff_percent, 100, 1e-12);
  EXPECT_NEAR(100 * (1 - p.upward_fraction), 58.0, 0.06);
  // sample_01: LORL 100 and DFF 99.99 agree with the data: no warning.
  EXPECT_TRUE(load_photometry(shared_file("eulumdat-analysis/sample_01.ldt")).warnings.empty());
}

TEST(PhotometryRealFiles, LorlThatDisagreesWithTheDataWarns) {
  test::TempDir dir;
  std::vector<std::string> lines;
  std::istringstream is(shared_text("eulumdat-analysis/sample_01.ldt"));
  for (std::string l; std::getline(is, l);) lines.push_back(l);
  lines[22] = "80";  // field 23 LORL
  std::string text;
  for (const std::string& l : lines) text += l + "\n";
  const Photometry p = load_photometry(dir.write("lorl.ldt", text));
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_NE(p.warnings[0].find("field 23 LORL states 80 %"), std::string::npos) << p.warnings[0];
}

// ---------------------------------------------------------------- synthetic webs

// An IES LM-63-2002 type C file with the given angles and I(C, gamma).
std::string make_ies(const std::vector<double>& gammas, const std::vector<double>& cs,
                     const std::function<double(double, double)>& cd, const std::string& factors = "1.0 1.0 50") {
  std::ostringstream os;
  os.precision(17);
  os << "IESNA:LM-63-2002\n[TEST] synthetic\n[MANUFAC] test\nTILT=NONE\n";
  os << "1 1000 1 " << gammas.size() << ' ' << cs.size() << " 1 2 0.5 0.5 0\n" << factors << "\n";
  for (double g : gammas) os << g << ' ';
  os << '\n';
  for (double c : cs) os << c << ' ';
  os << '\n';
  for (double c : cs) {
    for (double g : gammas) os << cd(c, g) << ' ';
    os << '\n';
  }
  return os.str();
}

// A EULUMDAT file: `mc` C planes of step 360/mc, the planes that Isym stores, cd/klm of 1000 lm.
std::string make_ldt(int isym, int mc, const std::vector<double>& gammas, const std::function<double(double, double)>& cd) {
  std::ostringstream os;
  os.precision(17);
  os << "test\n1\n" << isym << '\n' << mc << '\n' << 360.0 / mc << '\n' << gammas.size() << "\n0\n";
  os << "report\nluminaire\nnumber\nfile.ldt\ndate\n";
  os << "600\n600\n50\n600\n600\n0\n0\n0\n0\n";  // 13-21
  os << "100\n100\n1\n0\n1\n1\nLED\n1000\n4000\n80\n10\n";  // 22-26f
  for (int k = 0; k < 10; ++k) os << "0.5\n";
  std::vector<double> c_all;
  for (int k = 0; k < mc; ++k) c_all.push_back(360.0 * k / mc);
  for (double c : c_all) os << c << '\n';
  for (double g : gammas) os << g << '\n';
  std::vector<int> stored;
  switch (isym) {
    case 0: for (int k = 0; k < mc; ++k) stored.push_back(k); break;
    case 1: stored.push_back(0); break;
    case 2: for (int k = 0; k <= mc / 2; ++k) stored.push_back(k); break;
    case 3: for (int k = 0; k <= mc / 2; ++k) stored.push_back((3 * mc / 4 + k) % mc); break;
    default: for (int k = 0; k <= mc / 4; ++k) stored.push_back(k); break;
  }
  for (int j : stored) {
    for (double g : gammas) os << cd(c_all[static_cast<std::size_t>(j)], g) << '\n';
  }
  return os.str();
}

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> v;
  for (int i = 0; from + i * step <= to + 1e-9; ++i) v.push_back(from + i * step);
  return v;
}

double cosd(double deg) { return std::cos(deg * kPi / 180); }

TEST(PhotometryClosedForm, LambertianIntegratesToPiI0) {
  const double i0 = 1000;
  const auto lambert = [&](double, double g) { return g <= 90 ? i0 * std::max(0.0, cosd(g)) : 0.0; };
  // Trapezoid rule on cos g sin g = sin(2g)/2 with step h: relative error (2h)^2/12 = 1.015e-4.
  const double tol = 1.1e-4;
  const Photometry ies = parse_ies(make_ies(steps(0, 90, 1), {0}, lambert), "lambert.ies");
  EXPECT_NEAR(ies.luminaire_flux_lm / (kPi * i0), 1, tol);
  EXPECT_NEAR(ies.upward_fraction, 0, 1e-12);
  // The same as a EULUMDAT Isym 1 (cd/klm of 1000 lm = cd) and as a full Isym 0 web.
  const Photometry ldt1 = parse_eulumdat(make_ldt(1, 1, steps(0, 180, 1), lambert), "lambert1.ldt");
  EXPECT_NEAR(ldt1.luminaire_flux_lm / (kPi * i0), 1, tol);
  const Photometry ldt0 = parse_eulumdat(make_ldt(0, 24, steps(0, 180, 1), lambert), "lambert0.ldt");
  EXPECT_NEAR(ldt0.luminaire_flux_lm / (kPi * i0), 1, tol);
  // Interpolation between the 1-degree nodes follows the cosine closely.
  for (double g = 0.5; g < 89; g += 7.3) EXPECT_NEAR(ies.intensity_cd(17, g), i0 * cosd(g), 1e-3 * i0) << g;
  // And on a coarse 5-degree grid the PCHIP error stays below 0.3 % of I0.
  const Photometry coarse = parse_ies(make_ies(steps(0, 90, 5), {0}, lambert), "coarse.ies");
  for (double g = 2.5; g < 88; g += 5) EXPECT_NEAR(coarse.intensity_cd(0, g), i0 * cosd(g), 3e-3 * i0) << g;
}

TEST(PhotometryClosedForm, IsotropicIntegratesTo4PiI0InEverySymmetry) {
  const double i0 = 250;
  const auto iso = [&](double, double) { return i0; };
  const std::vector<double> g = steps(0, 180, 2.5);
  struct Case {
    std::string name;
    std::vector<double> cs;
    PhotometricSymmetry symmetry;
  };
  const std::vector<Case> ies_cases = {
      {"rotational", {0}, PhotometricSymmetry::rotational},
      {"quadrant", steps(0, 90, 22.5), PhotometricSymmetry::quadrant},
      {"bilateral", steps(0, 180, 15), PhotometricSymmetry::bilateral_c0_c180},
      {"old 90-270", steps(90, 270, 30), PhotometricSymmetry::bilateral_c90_c270},
      {"full", steps(0, 360, 10), PhotometricSymmetry::none},
      {"full, closed", steps(0, 350, 10), PhotometricSymmetry::none},
  };
  for (const Case& c : ies_cases) {
    SCOPED_TRACE(c.name);
    const Photometry p = parse_ies(make_ies(g, c.cs, iso), c.name + ".ies");
    EXPECT_EQ(p.symmetry, c.symmetry);
    EXPECT_NEAR(p.luminaire_flux_lm / (4 * kPi * i0), 1, 2e-4);
    EXPECT_NEAR(p.upward_fraction, 0.5, 1e-9);
    EXPECT_NEAR(p.intensity_cd(123.4, 77.7), i0, 1e-9);
  }
  for (int isym = 0; isym <= 4; ++isym) {
    SCOPED_TRACE("Isym " + std::to_string(isym));
    const Photometry p = parse_eulumdat(make_ldt(isym, 24, g, iso), "iso.ldt");
    EXPECT_NEAR(p.luminaire_flux_lm / (4 * kPi * i0), 1, 2e-4);
    EXPECT_NEAR(p.intensity_cd(301.2, 12.3), i0, 1e-9);
  }
}

// A distribution with no symmetry at all, to be folded by each symmetry.
double lumpy(double c, double g) {
  return 100 + 40 * cosd(c - 30) * std::sin(g * kPi / 180) + 25 * cosd(2 * c) + 0.2 * g;
}

TEST(PhotometrySymmetry, QuadrantBilateralAndRotationalFolds) {
  const std::vector<double> g = steps(0, 180, 5);
  // Quadrant (IES 0..90, EULUMDAT Isym 4): I(C) = I(180-C) = I(180+C) = I(360-C).
  for (const Photometry& p : {parse_ies(make_ies(g, steps(0, 90, 15), lumpy), "q.ies"),
                              parse_eulumdat(make_ldt(4, 24, g, lumpy), "q.ldt"),
                              load_photometry(shared_file("renderpipeline/overhead.ies"))}) {
    SCOPED_TRACE(p.path);
    EXPECT_EQ(p.symmetry, PhotometricSymmetry::quadrant);
    for (double c : {3.3, 17.0, 44.9, 61.2, 89.0}) {
      for (double gamma : {0.7, 33.3, 62.1, 88.8}) {
        const double i = p.intensity_cd(c, gamma);
        EXPECT_NEAR(p.intensity_cd(180 - c, gamma), i, 1e-9 * (1 + i));
        EXPECT_NEAR(p.intensity_cd(180 + c, gamma), i, 1e-9 * (1 + i));
        EXPECT_NEAR(p.intensity_cd(360 - c, gamma), i, 1e-9 * (1 + i));
        EXPECT_NEAR(p.intensity_cd(-c, gamma), i, 1e-9 * (1 + i));
      }
    }
  }
  // Bilateral about C0-C180 (IES 0..180, Isym 2): I(C) = I(360-C), and not I(180-C).
  for (const Photometry& p : {parse_ies(make_ies(g, steps(0, 180, 15), lumpy), "b.ies"),
                              parse_eulumdat(make_ldt(2, 24, g, lumpy), "b.ldt"),
                              load_photometry(shared_file("renderpipeline/medium_scatter.ies"))}) {
    SCOPED_TRACE(p.path);
    EXPECT_EQ(p.symmetry, PhotometricSymmetry::bilateral_c0_c180);
    for (double c : {3.3, 61.2, 100.0, 170.5}) {
      for (double gamma : {12.0, 45.5, 80.0}) {
        const double i = p.intensity_cd(c, gamma);
        EXPECT_NEAR(p.intensity_cd(360 - c, gamma), i, 1e-9 * (1 + i));
      }
    }
    if (p.path != "b.ies" && p.path != "b.ldt") continue;
    EXPECT_GT(std::abs(p.intensity_cd(30, 60) - p.intensity_cd(150, 60)), 10);
  }
  // Bilateral about C90-C270 (old IES 90..270, Isym 3 stored C270..C90): I(C) = I(180-C).
  for (const Photometry& p : {parse_ies(make_ies(g, steps(90, 270, 15), lumpy), "b90.ies"),
                              parse_eulumdat(make_ldt(3, 24, g, lumpy), "b90.ldt")}) {
    SCOPED_TRACE(p.path);
    EXPECT_EQ(p.symmetry, PhotometricSymmetry::bilateral_c90_c270);
    for (double c : {3.3, 61.2, 100.0, 170.5, 250.0, 300.0}) {
      for (double gamma : {12.0, 45.5, 80.0, 150.0}) {
        const double i = p.intensity_cd(c, gamma);
        EXPECT_NEAR(p.intensity_cd(180 - c, gamma), i, 1e-9 * (1 + i));
      }
    }
    // The stored half is reproduced at its nodes (IES 90..270; EULUMDAT Isym 3 C270..360..90).
    const std::vector<double> nodes = p.format == PhotometryFormat::ies ? std::vector<double>{90, 135, 180, 225, 270}
                                                                         : std::vector<double>{270, 315, 0, 45, 90};
    for (double c : nodes) EXPECT_NEAR(p.intensity_cd(c, 35), lumpy(c, 35), 1e-9) << c;
  }
  // Rotational: independent of C.
  const Photometry rot = load_photometry(shared_file("renderpipeline/bollard.ies"));
  for (double gamma : {3.0, 61.0, 91.0, 170.0}) {
    EXPECT_DOUBLE_EQ(rot.intensity_cd(0, gamma), rot.intensity_cd(211.7, gamma));
  }
}

TEST(PhotometryInterpolation, ReproducesTheFileAtItsNodes) {
  // area_light.ies: non-uniform C and gamma grids, candela multiplier 1.27.
  const Photometry p = load_photometry(shared_file("renderpipeline/area_light.ies"));
  EXPECT_NEAR(p.intensity_cd(0, 0), 7417.0 * 1.27, 1e-9);
  EXPECT_NEAR(p.intensity_cd(0, 45), 4547.0 * 1.27, 1e-9);   // 10th value of the C0 plane
  EXPECT_NEAR(p.intensity_cd(5, 45), 4606.0 * 1.27, 1e-9);   // 10th value of the C5 plane
  EXPECT_NEAR(p.intensity_cd(355, 45), 4606.0 * 1.27, 1e-9); // mirrored
  for (const char* name : {"renderpipeline/area_light.ies", "eulumdat-analysis/sample_20.ldt", "lidrs/example.ldt",
                           "radiance/examp1.ies"}) {
    const Photometry q = load_photometry(shared_file(name));
    for (std::size_t j = 0; j < q.c_angles_deg.size(); ++j) {
      for (std::size_t i = 0; i < q.gamma_angles_deg.size(); ++i) {
        const double node = q.candela_cd(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(i));
        ASSERT_NEAR(q.intensity_cd(q.c_angles_deg[j], q.gamma_angles_deg[i]), node, 1e-9 * (1 + node))
            << name << " C " << q.c_angles_deg[j] << " gamma " << q.gamma_angles_deg[i];
      }
    }
  }
}

TEST(PhotometryInterpolation, SmoothDistributionsBetweenPlanes) {
  // I = 100 + 50 cos(C - 20) on 15-degree planes: the cubic through the parabola slopes is
  // within 0.05 cd between planes (flat slopes would be off by ~0.8 cd, linear by ~0.4 cd).
  const auto f = [](double c, double) { return 100 + 50 * cosd(c - 20); };
  const Photometry p = parse_ies(make_ies(steps(0, 180, 5), steps(0, 360, 15), f), "wave.ies");
  double worst = 0;
  for (double c = 0.5; c < 360; c += 2.5) worst = std::max(worst, std::abs(p.intensity_cd(c, 40) - f(c, 40)));
  EXPECT_LT(worst, 0.05);
  // The same wave in gamma, 15 degrees of phase a step: PCHIP is within 0.13 cd (it flattens
  // at the extrema; linear would be off by 0.42 cd).
  const auto h = [](double, double g) { return 100 + 50 * cosd(3 * g); };
  const Photometry q = parse_ies(make_ies(steps(0, 180, 5), {0}, h), "gamma_wave.ies");
  worst = 0;
  for (double g = 0.3; g < 180; g += 1.1) worst = std::max(worst, std::abs(q.intensity_cd(0, g) - h(0, g)));
  EXPECT_LT(worst, 0.15);
}

TEST(PhotometryInterpolation, ShapePreservingAndContinuouslyDifferentiable) {
  const Photometry p = load_photometry(shared_file("renderpipeline/area_light.ies"));
  // Between two nodes the value stays within them (no overshoot), never below 0.
  const std::vector<double>& g = p.gamma_angles_deg;
  for (std::size_t i = 0; i + 1 < g.size(); ++i) {
    const double a = p.candela_cd(0, static_cast<Eigen::Index>(i)), b = p.candela_cd(0, static_cast<Eigen::Index>(i + 1));
    for (double t : {0.1, 0.5, 0.9}) {
      const double v = p.intensity_cd(0, g[i] + t * (g[i + 1] - g[i]));
      EXPECT_GE(v, std::min(a, b) - 1e-9);
      EXPECT_LE(v, std::max(a, b) + 1e-9);
    }
  }
  // C1: one-sided slopes agree at interior nodes (gamma 62.5 and C 47.5 are nodes).
  const double e = 1e-6;
  const auto slope_check = [&](const std::function<double(double)>& f, double x) {
    const double left = (f(x) - f(x - e)) / e, right = (f(x + e) - f(x)) / e;
    EXPECT_NEAR(left, right, 1e-3 * (1 + std::abs(left))) << x;
  };
  slope_check([&](double x) { return p.intensity_cd(20, x); }, 62.5);
  slope_check([&](double x) { return p.intensity_cd(20, x); }, 87.5);  // all planes equal there
  slope_check([&](double x) { return p.intensity_cd(20, x); }, 0.0 + 5);
  slope_check([&](double x) { return p.intensity_cd(x, 40); }, 47.5);
  slope_check([&](double x) { return p.intensity_cd(x, 40); }, 95);
  // Outside the measured gamma range: 0 (this web is 0..90).
  const Photometry down = load_photometry(shared_file("renderpipeline/overhead.ies"));
  EXPECT_GT(down.intensity_cd(0, 80), 0);
  EXPECT_EQ(down.intensity_cd(0, 90.5), 0);
  EXPECT_EQ(down.intensity_cd(0, 180), 0);
}

TEST(PhotometryDirection, LocalFrameMatchesCAndGamma) {
  EXPECT_TRUE(c_gamma_to_direction(0, 0).isApprox(Eigen::Vector3d(0, 0, -1)));
  EXPECT_TRUE(c_gamma_to_direction(0, 90).isApprox(Eigen::Vector3d(1, 0, 0)));
  EXPECT_TRUE(c_gamma_to_direction(90, 90).isApprox(Eigen::Vector3d(0, 1, 0)));
  EXPECT_TRUE(c_gamma_to_direction(0, 180).isApprox(Eigen::Vector3d(0, 0, 1)));
  for (const char* name : {"renderpipeline/medium_scatter.ies", "renderpipeline/area_light.ies", "lidrs/example.ldt"}) {
    SCOPED_TRACE(name);
    const Photometry p = load_photometry(shared_file(name));
    // Axis directions by hand: nadir, C0 at 45 degrees (+x down), C90 at 45 (+y down).
    EXPECT_NEAR(p.intensity_cd(Eigen::Vector3d(0, 0, -1)), p.intensity_cd(0, 0), 1e-9);
    EXPECT_NEAR(p.intensity_cd(Eigen::Vector3d(2, 0, -2)), p.intensity_cd(0, 45), 1e-9);
    EXPECT_NEAR(p.intensity_cd(Eigen::Vector3d(0, 1, -1)), p.intensity_cd(90, 45), 1e-9);
    EXPECT_NEAR(p.intensity_cd(Eigen::Vector3d(-1, 0, -1)), p.intensity_cd(180, 45), 1e-9);
    EXPECT_NEAR(p.intensity_cd(Eigen::Vector3d(0, -1, -1)), p.intensity_cd(270, 45), 1e-9);
    EXPECT_EQ(p.intensity_cd(Eigen::Vector3d(0, 0, 0)), 0);
    // Rotating the luminaire by 90 degrees about z (a direction d in the room is d rotated by
    // -90 in the luminaire) moves its pattern from C to C + 90.
    for (double c : {10.0, 75.0, 130.0, 200.0, 333.0}) {
      for (double gamma : {20.0, 50.0, 70.0}) {
        const Eigen::Vector3d d = c_gamma_to_direction(c, gamma);
        const Eigen::Vector2d back = direction_to_c_gamma_deg(d);
        EXPECT_NEAR(back.x(), c, 1e-9);
        EXPECT_NEAR(back.y(), gamma, 1e-9);
        EXPECT_NEAR(p.intensity_cd(d), p.intensity_cd(c, gamma), 1e-9 * (1 + p.intensity_cd(c, gamma)));
        const Eigen::Vector3d room = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()) * d;
        const Eigen::Vector2d cg = direction_to_c_gamma_deg(room);
        EXPECT_NEAR(cg.x(), std::fmod(c + 90, 360), 1e-9);
        const Eigen::Vector3d local = Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitZ()) * room;
        EXPECT_NEAR(p.intensity_cd(local), p.intensity_cd(c, gamma), 1e-9 * (1 + p.intensity_cd(c, gamma)));
      }
    }
  }
  // medium_scatter is a wash light: its pattern really is asymmetric (C0 != C180).
  const Photometry wash = load_photometry(shared_file("renderpipeline/medium_scatter.ies"));
  EXPECT_GT(std::abs(wash.intensity_cd(0, 60) - wash.intensity_cd(180, 60)), 0.2 * wash.intensity_cd(0, 60));
}

// ---------------------------------------------------------------- layout variants

std::string replace_first(std::string s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

TEST(PhotometryLayout, LineEndingsBomAndExtensions) {
  test::TempDir dir;
  const std::string lf = shared_text("renderpipeline/overhead.ies");
  const double flux = parse_ies(lf, "lf").luminaire_flux_lm;
  EXPECT_DOUBLE_EQ(parse_ies(replace_all(lf, "\n", "\r\n"), "crlf").luminaire_flux_lm, flux);
  EXPECT_DOUBLE_EQ(parse_ies(replace_all(lf, "\n", "\r"), "cr").luminaire_flux_lm, flux);
  EXPECT_DOUBLE_EQ(parse_ies("\xEF\xBB\xBF" + lf, "bom").luminaire_flux_lm, flux);
  EXPECT_DOUBLE_EQ(parse_ies(lf + "END\n\x1A garbage", "end").luminaire_flux_lm, flux);
  EXPECT_DOUBLE_EQ(parse_ies(replace_all(lf, " ", ","), "commas").luminaire_flux_lm, flux);
  // By extension, case-insensitive, and by content for other names.
  EXPECT_EQ(load_photometry(dir.write("A.IES", lf)).format, PhotometryFormat::ies);
  EXPECT_EQ(load_photometry(dir.write("a.txt", lf)).format, PhotometryFormat::ies);
  const std::string ldt = shared_text("eulumdat-analysis/sample_17.ldt");
  EXPECT_EQ(load_photometry(dir.write("B.LDT", ldt)).format, PhotometryFormat::eulumdat);
  EXPECT_EQ(load_photometry(dir.write("b.dat", ldt)).format, PhotometryFormat::eulumdat);
  EXPECT_DOUBLE_EQ(load_photometry(dir.write("b2.dat", ldt)).luminaire_flux_lm,
                   load_photometry(shared_file("eulumdat-analysis/sample_17.ldt")).luminaire_flux_lm);
  // The 1986 one-number-per-line file has its data across lines; all on one line is the same.
  const std::string old = shared_text("renderpipeline/defined_diffuse.ies");
  const std::size_t data = old.find("TILT=NONE\n") + 10;
  const std::string one_line = old.substr(0, data) + replace_all(old.substr(data), "\n", " ");
  EXPECT_DOUBLE_EQ(parse_ies(one_line, "one line").luminaire_flux_lm, parse_ies(old, "old").luminaire_flux_lm);
  EXPECT_THROW(load_photometry(dir.file("missing.ies")), PhotometryError);
  std::filesystem::create_directories(dir.file("folder.ies"));
  try {
    load_photometry(dir.file("folder.ies"));
    ADD_FAILURE() << "a folder was read";
  } catch (const PhotometryError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

TEST(PhotometryLayout, Iso88591TextBecomesUtf8) {
  std::string text = make_ldt(1, 1, steps(0, 90, 5), [](double, double g) { return 100 * cosd(g); });
  text = replace_first(text, "luminaire\n", "Leuchte f\xFCr B\xFCro\n");
  EXPECT_EQ(parse_eulumdat(text, "latin1.ldt").luminaire, "Leuchte f\xC3\xBCr B\xC3\xBCro");
  // Decimal commas (some European writers) read as points.
  text = replace_first(text, "\n0.5\n", "\n0,5\n");
  EXPECT_NO_THROW(parse_eulumdat(text, "comma.ldt"));
}

TEST(PhotometryScaling, BallastFactorsUnitsAndAbsolutePhotometry) {
  const std::string f1995 = shared_text("renderpipeline/overhead.ies");  // LM-63-1995
  const double flux = parse_ies(f1995, "x").luminaire_flux_lm;
  // Before 2002 the second factor (ballast-lamp photometric factor) scales candela too.
  EXPECT_NEAR(parse_ies(replace_first(f1995, "1.0000    1.0000  432", "0.5000    1.0000  432"), "bf").luminaire_flux_lm,
              0.5 * flux, 1e-9 * flux);
  EXPECT_NEAR(parse_ies(replace_first(f1995, "1.0000    1.0000  432", "1.0000    0.8000  432"), "blf").luminaire_flux_lm,
              0.8 * flux, 1e-9 * flux);
  const std::string f2002 = shared_text("renderpipeline/medium_scatter.ies");
  const double flux2 = parse_ies(f2002, "y").luminaire_flux_lm;
  // In LM-63-2002 that field is "future use": ignored.
  EXPECT_DOUBLE_EQ(parse_ies(replace_first(f2002, "1.0 1.0 24", "1.0 0.5 24"), "fu").luminaire_flux_lm, flux2);
  // Candela multiplier scales candela, not the stated lamp flux.
  const Photometry m = parse_ies(replace_first(f2002, "1 1615 1 37", "1 1615 2 37"), "m");
  EXPECT_NEAR(m.luminaire_flux_lm, 2 * flux2, 1e-9 * flux2);
  EXPECT_DOUBLE_EQ(m.lamp_flux_lm, 1615);
  // Absolute photometry: lumens per lamp = -1.
  const Photometry a = parse_ies(replace_first(f2002, "1 1615 1 37", "1 -1 1 37"), "abs");
  EXPECT_TRUE(a.absolute);
  EXPECT_DOUBLE_EQ(a.lamp_flux_lm, a.luminaire_flux_lm);
  EXPECT_DOUBLE_EQ(a.luminaire_flux_lm, flux2);
  // Units: the same numbers in feet are 0.3048 x the metres.
  const Photometry feet = parse_ies(replace_first(f2002, "1 2 0.103 0.059 0", "1 1 0.103 0.059 0"), "ft");
  EXPECT_NEAR(feet.opening.width_m, 0.103 * 0.3048, 1e-12);
  // Disc: negative width, zero height.
  const Photometry disc = parse_ies(replace_first(f2002, "1 2 0.103 0.059 0", "1 2 -0.2 -0.2 0"), "disc");
  EXPECT_EQ(disc.opening.shape, OpeningShape::disc);
  EXPECT_DOUBLE_EQ(disc.opening.width_m, 0.2);
  // EULUMDAT: cd/klm x lamp set 1 flux / 1000 x conversion factor (field 24).
  std::string ldt = make_ldt(1, 1, steps(0, 90, 5), [](double, double g) { return 100 * cosd(g); });
  const double rel = parse_eulumdat(ldt, "rel").luminaire_flux_lm;
  ldt = replace_first(ldt, "\n100\n100\n1\n0\n1\n1\nLED\n1000\n", "\n100\n100\n1.5\n0\n1\n1\nLED\n3000\n");
  EXPECT_NEAR(parse_eulumdat(ldt, "scaled").luminaire_flux_lm, 4.5 * rel, 1e-9 * rel);
}

// ---------------------------------------------------------------- malformed files

struct Broken {
  std::string name;       // test case
  std::string source;     // shared file to mutate
  std::function<std::string(const std::string&)> mutate;
  int line;               // expected line in the message
  std::string field;      // expected "field NAME"
  std::string what;       // expected part of the explanation
};

// Replaces the whole line `n` (1-based).
std::function<std::string(const std::string&)> set_line(int n, const std::string& value) {
  return [n, value](const std::string& s) {
    std::vector<std::string> lines;
    std::istringstream is(s);
    for (std::string l; std::getline(is, l);) lines.push_back(l);
    lines.at(static_cast<std::size_t>(n - 1)) = value;
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
  };
}
std::function<std::string(const std::string&)> replace(const std::string& from, const std::string& to) {
  return [from, to](const std::string& s) { return replace_first(s, from, to); };
}

TEST(PhotometryMalformed, EveryClassFailsWithFileLineAndField) {
  const std::string ies = "renderpipeline/overhead.ies";      // 24 lines, data from line 15
  const std::string ldt = "eulumdat-analysis/sample_01.ldt";  // one field a line; C angles 43-66, gamma 67-103
  const std::vector<Broken> cases = {
      {"truncated ies", ies, [](const std::string& s) { return s.substr(0, s.size() - 200); }, 10, "candela",
       "truncated or wrong counts"},
      {"too many values ies", ies, [](const std::string& s) { return s + "1 2 3\n"; }, 25, "candela",
       "3 more values after the 95"},
      {"count too high ies", ies, replace("   19    5    1", "   19    6    1"), 10, "candela", "truncated or wrong counts"},
      {"count too low ies", ies, replace("   19    5    1", "   19    4    1"), 14, "horizontal angles",
       "not a valid type C symmetry"},
      {"gigabyte counts ies", ies, replace("   19    5    1", "   9000000    9000000    1"), 10, "candela",
       "truncated or wrong counts"},
      {"absurd count ies", ies, replace("   19    5    1", "   1e12    5    1"), 10, "number of vertical angles", "outside"},
      {"negative candela", ies, replace(" 19229. 19192.", " 19229. -19192."), 15,
       "candela[C=0, gamma=5]", "negative"},
      {"nan candela", ies, replace(" 19229. 19192.", " 19229. nan"), 15, "candela[C=0, gamma=5]", "not a finite number"},
      {"inf candela", ies, replace(" 19229. 19192.", " 19229. inf"), 15, "candela[C=0, gamma=5]", "not a finite number"},
      {"1e300 candela", ies, replace(" 19229. 19192.", " 19229. 1e300"), 15, "candela[C=0, gamma=5]",
       "beyond any luminaire"},
      {"1e400 candela", ies, replace(" 19229. 19192.", " 19229. 1e400"), 15, "candela[C=0, gamma=5]",
       "not a finite number"},
      {"text in data", ies, replace(" 19229. 19192.", " 19229. abc"), 15, "candela[C=0, gamma=5]", "'abc'"},
      {"non-monotonic vertical", ies, replace("   15.0   20.0", "   20.0   15.0"), 12, "vertical angles[4]",
       "does not rise"},
      {"non-monotonic horizontal", ies, replace("   45.0   67.5", "   67.5   45.0"), 14, "horizontal angles[3]",
       "does not rise"},
      {"vertical beyond 180", ies, replace("   85.0   90.0", "   85.0  190.0"), 13, "vertical angles[18]", "outside"},
      {"invalid symmetry", ies, replace("22.5   45.0   67.5   90.0", "10.0   20.0   30.0   40.0"), 14,
       "horizontal angles", "not a valid type C symmetry"},
      {"type B", ies, replace("   19    5    1    1", "   19    5    2    1"), 10, "photometric type", "type B (2)"},
      {"type A", ies, replace("   19    5    1    1", "   19    5    3    1"), 10, "photometric type", "type A (3)"},
      {"unknown type", ies, replace("   19    5    1    1", "   19    5    7    1"), 10, "photometric type",
       "unknown type 7"},
      {"unknown units", ies, replace("   19    5    1    1", "   19    5    1    3"), 10, "units type", "outside"},
      {"tilt file", ies, replace("TILT=NONE", "TILT=lamp.tlt"), 9, "TILT", "not supported"},
      {"no tilt", ies, replace("TILT=NONE", "TILT NONE"), 24, "TILT", "no TILT= line"},
      {"zero multiplier", ies, replace("5000.  1.000000", "5000.  0"), 10, "candela multiplier", "must be > 0"},
      {"zero lumens", ies, replace("5000.  1.000000", "0  1.000000"), 10, "lumens per lamp", "-1 for absolute"},
      {"negative watts", ies, replace("432.0000", "-432"), 11, "input watts", "outside"},
      {"all zero", ies,
       [](const std::string& s) {
         std::string out = s.substr(0, s.find(" 19229."));
         for (int i = 0; i < 95; ++i) out += " 0";
         return out + "\n";
       },
       15, "candela", "every value is 0"},
      {"empty ies", ies, [](const std::string&) { return std::string(); }, 1, "identifier", "empty"},
      // EULUMDAT
      {"truncated ldt", ldt, [](const std::string& s) { return s.substr(0, s.size() / 2); }, 4, "4 Mc",
       "truncated or wrong counts"},
      {"header only ldt", ldt, [](const std::string& s) { return s.substr(0, 60); }, 11, "12 date/user",
       "truncated"},
      {"too many values ldt", ldt, [](const std::string& s) { return s + "12.5\n"; }, 585, "30 intensities",
       "more values after the 481"},
      {"unknown Isym", ldt, set_line(3, "5"), 3, "3 Isym", "unknown symmetry indicator 5"},
      {"unknown Ityp", ldt, set_line(2, "9"), 2, "2 Ityp", "unknown type indicator 9"},
      {"Mc odd for Isym 2", ldt, set_line(4, "23"), 4, "4 Mc", "multiple of 2"},
      {"gigabyte Ng", ldt, set_line(6, "5000000"), 4, "4 Mc", "truncated or wrong counts"},
      {"C angles not a symmetry", ldt, set_line(55, "179"), 55, "28 C angle[12]", "not a valid symmetry"},
      {"non-monotonic C", ldt, set_line(44, "0"), 44, "28 C angle[1]", "does not rise"},
      {"non-monotonic gamma", ldt, set_line(69, "5"), 69, "29 gamma angle[2]", "does not rise"},
      {"negative intensity", ldt, set_line(105, "-3"), 105, "30 intensity[C=0, gamma=5]", "negative"},
      {"nan intensity", ldt, set_line(105, "NaN"), 105, "30 intensity[C=0, gamma=5]", "not a finite number"},
      {"zero lamp flux", ldt, set_line(29, "0"), 29, "26c total luminous flux (lamp set 1)", "must be > 0"},
      {"zero lamps", ldt, set_line(27, "0"), 27, "26a number of lamps (lamp set 1)", "0 lamps"},
      {"text for a number", ldt, set_line(23, "n/a"), 23, "23 LORL", "'n/a' is not a finite number"},
  };
  test::TempDir dir;
  for (const Broken& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string ext = c.source.substr(c.source.size() - 4);
    std::string file_name = c.name;
    for (char& ch : file_name) {
      if (ch == ' ') ch = '_';
    }
    const std::string path = dir.write(file_name + ext, c.mutate(shared_text(c.source)));
    try {
      load_photometry(path);
      ADD_FAILURE() << "no error";
    } catch (const PhotometryError& e) {
      const std::string msg = e.what();
      const std::string expected_prefix =
          c.line > 0 ? path + ":" + std::to_string(c.line) + ": field " + c.field + ": " : path + ":";
      EXPECT_EQ(msg.rfind(expected_prefix, 0), 0u) << msg << "\n expected prefix " << expected_prefix;
      EXPECT_NE(msg.find("field " + c.field + ": "), std::string::npos) << msg;
      EXPECT_NE(msg.find(c.what), std::string::npos) << msg;
    }
  }
}

}  // namespace
}  // namespace ilp
