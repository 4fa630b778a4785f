// From the job's luminaire products (luminaires.products) to the variants a search
// tries: each product at each of its rotations (core/light/luminaire_product.h).
#pragma once

#include <vector>

#include "core/light/luminaire_product.h"
#include "job/config.h"

namespace ilp {

// Every product at every rotation, in the job's order. Throws ConfigError naming the
// config's file:line and key for a photometric file that cannot be read (with the
// file's own line and field) or that lacks what the product needs (watts).
std::vector<ProductVariant> product_variants(const LuminaireSearch& search);

}  // namespace ilp
