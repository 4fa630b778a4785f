// `ilp ugr-table FILE`: the CIE 190 UGR table of a photometric file (core/glare/ugr_table.h).
#include <cstdio>
#include <iostream>

#include "apps/commands.h"
#include "core/glare/ugr_table.h"
#include "core/light/photometry.h"

namespace ilp::cli {
namespace {

void print_csv(const UgrTable& t) {
  for (Eigen::Index r = 0; r < t.crosswise.rows(); ++r) {
    for (const Eigen::MatrixXd* m : {&t.crosswise, &t.endwise})
      for (Eigen::Index f = 0; f < m->cols(); ++f)
        std::printf("%s%.2f", (m == &t.crosswise && f == 0) ? "" : ",", (*m)(r, f));
    std::printf("\n");
  }
}

}  // namespace

int run_ugr_table(const UgrTableArgs& args) {
  const Photometry p = load_photometry(args.file);
  UgrTableOptions options;
  if (args.levin_formula) options.position_index = PositionIndexMethod::levin_formula;
  const UgrTable t = ugr_table(p, options);
  if (args.csv) {
    print_csv(t);
    return 0;
  }
  const LuminousOpening& o = p.opening;
  std::printf("%s  %s\n", args.file.c_str(), p.luminaire.c_str());
  std::printf("flux %.1f lm (the file's web), luminous opening %.3f x %.3f m, sides %.3f m\n", p.luminaire_flux_lm,
              o.length_m, o.width_m, o.height_m);
  std::printf("CIE 190 UGR table: spacing 0.25H, H = luminaires above the eye; crosswise = line of sight in the C0-C180 "
              "plane, endwise = in C90-C270; position index %s\n",
              args.levin_formula ? "by Levin's formula (not CIE 117's table)" : "from CIE 117 Table 4.1");
  std::cout << format_ugr_table(t);
  return 0;
}

}  // namespace ilp::cli
