// IDAS' vector operations compiled here (solvers/serial_vector_ops.hpp) against SUNDIALS' own
// serial implementations: the same bits for every operation and every special case, so that
// installing them cannot change a run.
#include <catch2/catch.hpp>
#include <sundials/sundials_context.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "cranesim/solvers/serial_vector_ops.hpp"

namespace {

class Vectors {
 public:
  explicit Vectors(int n) : n_(n) { SUNContext_Create(nullptr, &ctx_); }
  ~Vectors() {
    for (N_Vector v : owned_) N_VDestroy(v);
    SUNContext_Free(&ctx_);
  }
  /// A vector of random entries spread over many magnitudes, with the library's or the compiled ops.
  N_Vector random(bool compiled, unsigned seed) {
    N_Vector v = make(compiled);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-12, 6);
    for (int i = 0; i < n_; ++i) NV_Ith_S(v, i) = std::ldexp(mantissa(rng), exponent(rng));
    return v;
  }
  N_Vector copy(N_Vector of, bool compiled) {
    N_Vector v = make(compiled);
    std::memcpy(NV_DATA_S(v), NV_DATA_S(of), sizeof(double) * n_);
    return v;
  }
  N_Vector make(bool compiled) {
    N_Vector v = N_VNew_Serial(n_, ctx_);
    if (compiled) cranesim::useCompiledSerialOps(v);
    owned_.push_back(v);
    return v;
  }

 private:
  int n_;
  SUNContext ctx_ = nullptr;
  std::vector<N_Vector> owned_;
};

bool sameBits(N_Vector a, N_Vector b) {
  return std::memcmp(NV_DATA_S(a), NV_DATA_S(b), sizeof(double) * NV_LENGTH_S(a)) == 0;
}
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("compiled serial vector ops give SUNDIALS' own bits", "[vector_ops]") {
  const int n = 143;
  Vectors vs(n);
  // Every branch of N_VLinearSum: a, b = ±1, a = ±b, general; and the in-place axpy forms.
  const std::vector<std::pair<double, double>> coefficients = {
      {1, 1}, {1, -1}, {-1, 1}, {1, 0.3}, {0.3, 1}, {-1, 0.3}, {0.3, -1}, {0.7, 0.7}, {0.7, -0.7}, {0.3, 0.9}, {-1, -1}, {2.5, 0}};
  for (const auto& [a, b] : coefficients)
    for (int alias = 0; alias < 3; ++alias) {  // z separate, z = x, z = y
      CAPTURE(a, b, alias);
      N_Vector x0 = vs.random(false, 1), y0 = vs.random(false, 2), z0 = vs.random(false, 3);
      N_Vector x1 = vs.copy(x0, true), y1 = vs.copy(y0, true), z1 = vs.copy(z0, true);
      N_Vector out0 = alias == 0 ? z0 : alias == 1 ? x0 : y0, out1 = alias == 0 ? z1 : alias == 1 ? x1 : y1;
      N_VLinearSum_Serial(a, x0, b, y0, out0);
      N_VLinearSum(a, x1, b, y1, out1);
      CHECK(sameBits(out0, out1));
    }
  for (double c : {1.0, -1.0, 0.37}) {
    for (bool in_place : {false, true}) {
      N_Vector x0 = vs.random(false, 4), z0 = vs.random(false, 5);
      N_Vector x1 = vs.copy(x0, true), z1 = vs.copy(z0, true);
      N_VScale_Serial(c, x0, in_place ? x0 : z0);
      N_VScale(c, x1, in_place ? x1 : z1);
      CHECK(sameBits(in_place ? x0 : z0, in_place ? x1 : z1));
    }
  }
  N_Vector x0 = vs.random(false, 6), y0 = vs.random(false, 7), z0 = vs.make(false);
  N_Vector x1 = vs.copy(x0, true), y1 = vs.copy(y0, true), z1 = vs.make(true);
  N_VProd_Serial(x0, y0, z0), N_VProd(x1, y1, z1);
  CHECK(sameBits(z0, z1));
  N_VDiv_Serial(x0, y0, z0), N_VDiv(x1, y1, z1);
  CHECK(sameBits(z0, z1));
  N_VAbs_Serial(x0, z0), N_VAbs(x1, z1);
  CHECK(sameBits(z0, z1));
  N_VInv_Serial(x0, z0), N_VInv(x1, z1);
  CHECK(sameBits(z0, z1));
  N_VAddConst_Serial(x0, 0.123, z0), N_VAddConst(x1, 0.123, z1);
  CHECK(sameBits(z0, z1));
  N_VConst_Serial(-4.5, z0), N_VConst(-4.5, z1);
  CHECK(sameBits(z0, z1));
  CHECK(sameBits(N_VDotProd_Serial(x0, y0), N_VDotProd(x1, y1)));
  CHECK(sameBits(N_VMaxNorm_Serial(x0), N_VMaxNorm(x1)));
  CHECK(sameBits(N_VWrmsNorm_Serial(x0, y0), N_VWrmsNorm(x1, y1)));
  CHECK(sameBits(N_VWSqrSumLocal_Serial(x0, y0), N_VWSqrSumLocal(x1, y1)));
  // The mask as IDAS sets it (1 differential, 0 algebraic), with a NaN among the masked entries:
  // it must stay out of the sum as in the library's branch.
  N_Vector id0 = vs.make(false), id1 = vs.make(true);
  for (int i = 0; i < n; ++i) NV_Ith_S(id0, i) = NV_Ith_S(id1, i) = (i % 7 == 3 || i > 120) ? 0.0 : 1.0;
  NV_Ith_S(x0, 130) = NV_Ith_S(x1, 130) = std::numeric_limits<double>::quiet_NaN();
  const double masked = N_VWrmsNormMask(x1, y1, id1);
  CHECK(std::isfinite(masked));
  CHECK(sameBits(N_VWrmsNormMask_Serial(x0, y0, id0), masked));
  CHECK(sameBits(N_VWSqrSumMaskLocal_Serial(x0, y0, id0), N_VWSqrSumMaskLocal(x1, y1, id1)));
}

TEST_CASE("IDAS' clones of a vector keep the compiled ops", "[vector_ops]") {
  Vectors vs(10);
  N_Vector v = vs.make(true);
  N_Vector clone = N_VClone(v);
  CHECK(clone->ops->nvwrmsnormmask == v->ops->nvwrmsnormmask);
  CHECK(clone->ops->nvlinearsum == v->ops->nvlinearsum);
  CHECK(clone->ops->nvwrmsnormmask != &N_VWrmsNormMask_Serial);
  N_VDestroy(clone);
}
