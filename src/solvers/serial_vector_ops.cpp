#include "cranesim/solvers/serial_vector_ops.hpp"

#include <cmath>
#include <stdexcept>

namespace cranesim {
namespace {

// Every loop below is the serial vector's own definition (SUNDIALS' N_Vector interface), written
// with the same operations in the same order, so that the results do not change in the last bit.

struct Data {
  sunrealtype* p;
  sunindextype n;
};
Data data(N_Vector v) { return {NV_DATA_S(v), NV_LENGTH_S(v)}; }

void axpy(sunrealtype a, N_Vector x, N_Vector y) {  // y ← a x + y
  const auto [xd, n] = data(x);
  sunrealtype* yd = NV_DATA_S(y);
  if (a == 1.0) {
    for (sunindextype i = 0; i < n; ++i) yd[i] += xd[i];
  } else if (a == -1.0) {
    for (sunindextype i = 0; i < n; ++i) yd[i] -= xd[i];
  } else {
    for (sunindextype i = 0; i < n; ++i) yd[i] += a * xd[i];
  }
}

/// z = a x + b y with the serial vector's special cases: each computes the value in its own way
/// (c (x + y) is not c x + c y to the last bit), so they are kept as they are.
void linearSum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z) {
  if (b == 1.0 && z == y) return axpy(a, x, y);
  if (a == 1.0 && z == x) return axpy(b, y, x);
  const auto [xd, n] = data(x);
  const sunrealtype* yd = NV_DATA_S(y);
  sunrealtype* zd = NV_DATA_S(z);
  if (a == 1.0 && b == 1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] + yd[i];
  } else if (a == 1.0 && b == -1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] - yd[i];
  } else if (a == -1.0 && b == 1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = yd[i] - xd[i];
  } else if (a == 1.0) {  // b y + x
    for (sunindextype i = 0; i < n; ++i) zd[i] = (b * yd[i]) + xd[i];
  } else if (b == 1.0) {  // a x + y
    for (sunindextype i = 0; i < n; ++i) zd[i] = (a * xd[i]) + yd[i];
  } else if (a == -1.0) {  // b y − x
    for (sunindextype i = 0; i < n; ++i) zd[i] = (b * yd[i]) - xd[i];
  } else if (b == -1.0) {  // a x − y
    for (sunindextype i = 0; i < n; ++i) zd[i] = (a * xd[i]) - yd[i];
  } else if (a == b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (a == -b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = (a * xd[i]) + (b * yd[i]);
  }
}

void constant(sunrealtype c, N_Vector z) {
  const auto [zd, n] = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c;
}

void product(N_Vector x, N_Vector y, N_Vector z) {
  const auto [xd, n] = data(x);
  const sunrealtype* yd = NV_DATA_S(y);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] * yd[i];
}

void quotient(N_Vector x, N_Vector y, N_Vector z) {
  const auto [xd, n] = data(x);
  const sunrealtype* yd = NV_DATA_S(y);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] / yd[i];
}

void scale(sunrealtype c, N_Vector x, N_Vector z) {
  const auto [xd, n] = data(x);
  sunrealtype* zd = NV_DATA_S(z);
  if (z == x) {
    for (sunindextype i = 0; i < n; ++i) zd[i] *= c;
  } else if (c == 1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i];
  } else if (c == -1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = -xd[i];
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = c * xd[i];
  }
}

void absolute(N_Vector x, N_Vector z) {
  const auto [xd, n] = data(x);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = std::abs(xd[i]);
}

void inverse(N_Vector x, N_Vector z) {
  const auto [xd, n] = data(x);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = 1.0 / xd[i];
}

void addConstant(N_Vector x, sunrealtype b, N_Vector z) {
  const auto [xd, n] = data(x);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] + b;
}

sunrealtype dotProduct(N_Vector x, N_Vector y) {
  const auto [xd, n] = data(x);
  const sunrealtype* yd = NV_DATA_S(y);
  sunrealtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) sum += xd[i] * yd[i];
  return sum;
}

sunrealtype maxNorm(N_Vector x) {
  const auto [xd, n] = data(x);
  sunrealtype max = 0.0;
  for (sunindextype i = 0; i < n; ++i)
    if (std::abs(xd[i]) > max) max = std::abs(xd[i]);
  return max;
}

sunrealtype weightedSquareSum(N_Vector x, N_Vector w) {
  const auto [xd, n] = data(x);
  const sunrealtype* wd = NV_DATA_S(w);
  sunrealtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    const sunrealtype p = xd[i] * wd[i];
    sum += p * p;
  }
  return sum;
}

/// The masked sum skips entries with id ≤ 0; selecting 0 instead of branching adds +0.0 there,
/// which leaves the (non-negative) sum unchanged.
sunrealtype weightedSquareSumMasked(N_Vector x, N_Vector w, N_Vector id) {
  const auto [xd, n] = data(x);
  const sunrealtype *wd = NV_DATA_S(w), *idd = NV_DATA_S(id);
  sunrealtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    const sunrealtype p = xd[i] * wd[i];
    sum += idd[i] > 0.0 ? p * p : 0.0;
  }
  return sum;
}

sunrealtype weightedRmsNorm(N_Vector x, N_Vector w) {
  return std::sqrt(weightedSquareSum(x, w) / NV_LENGTH_S(x));
}

sunrealtype weightedRmsNormMasked(N_Vector x, N_Vector w, N_Vector id) {
  return std::sqrt(weightedSquareSumMasked(x, w, id) / NV_LENGTH_S(x));
}

}  // namespace

void useCompiledSerialOps(N_Vector v) {
  if (v == nullptr || N_VGetVectorID(v) != SUNDIALS_NVEC_SERIAL)
    throw std::invalid_argument("useCompiledSerialOps: not a serial N_Vector");
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = linearSum;
  ops->nvconst = constant;
  ops->nvprod = product;
  ops->nvdiv = quotient;
  ops->nvscale = scale;
  ops->nvabs = absolute;
  ops->nvinv = inverse;
  ops->nvaddconst = addConstant;
  ops->nvdotprod = dotProduct;
  ops->nvmaxnorm = maxNorm;
  ops->nvwrmsnorm = weightedRmsNorm;
  ops->nvwrmsnormmask = weightedRmsNormMasked;
  ops->nvwsqrsumlocal = weightedSquareSum;
  ops->nvwsqrsummasklocal = weightedSquareSumMasked;
}

}  // namespace cranesim
