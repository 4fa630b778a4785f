// From the job's luminaire products (luminaires.products) to the variants a search
// tries: each product at each of its rotations (core/light/luminaire_product.h).
#pragma once

#include <vector>

#include "core/light/luminaire_product.h"
#include "job/config.h"

namespace ilp {

// One product as a variant at rotation 0: its type (the photometric file read here,
// or the square panel), rated flux, watts, dimming range, maintenance factor and
// suspension. Throws ConfigError naming the config's file:line and key for a
// photometric file that cannot be read (with the file's own line and field) or that
// lacks what the product needs (watts).
ProductVariant product_base(const ProductSetting& product);

// Every product at every rotation, in the job's order (product_base, then each
// rotation). A product without rotations_deg gets [0] when rotationally symmetric or
// wall_mounted (C0 into the room), else [0, 90]. Throws as product_base.
std::vector<ProductVariant> product_variants(const std::vector<ProductSetting>& products, bool wall_mounted = false);

}  // namespace ilp
