// The one numerical kernel of the streamed least squares: new rows B folded into an upper
// triangular factor R by Householder reflections, R <- the R of the QR of [R; B], exploiting
// that R is triangular (each reflection touches one row of R and all rows of B).
#pragma once

#include <cstddef>

namespace modelgen::detail {

/// R (w x w, upper triangular, column-major, leading dimension ldr) becomes the triangular
/// factor of [R; B] for B (m x w, column-major, leading dimension ldb); B is used as scratch
/// and holds no meaning afterwards. R's strictly lower part is neither read nor written.
/// The same reflections as a dense Householder QR of the stack (LAPACK dlarfg convention,
/// diagonal of either sign), applied to B in row chunks.
/// NaN or infinity in B or R ends up in R.
void fold_rows(double* R, std::ptrdiff_t ldr, double* B, std::ptrdiff_t ldb, std::ptrdiff_t m,
               std::ptrdiff_t w);

}  // namespace modelgen::detail
