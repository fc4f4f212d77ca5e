#pragma once
// What both minimum-time collocations share as Ipopt problems: the decision vector ends with
// the final time t_f, the objective is t_f, the search starts from a given point, and the
// solution is kept. A problem adds its sizes, bounds and constraints.

#include <IpTNLP.hpp>

#include <algorithm>
#include <utility>
#include <vector>

namespace cranesim {

class FinalTimeTnlp : public Ipopt::TNLP {
 public:
  explicit FinalTimeTnlp(std::vector<double> start) : start_(std::move(start)) {}

  std::vector<double> solution;

  bool get_starting_point(Ipopt::Index n, bool, Ipopt::Number* z, bool, Ipopt::Number*, Ipopt::Number*, Ipopt::Index,
                          bool, Ipopt::Number*) override {
    std::copy(start_.begin(), start_.begin() + n, z);
    return true;
  }

  bool eval_f(Ipopt::Index n, const Ipopt::Number* z, bool, Ipopt::Number& objective) override {
    objective = z[n - 1];
    return true;
  }

  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number*, bool, Ipopt::Number* gradient) override {
    std::fill(gradient, gradient + n, 0.0);
    gradient[n - 1] = 1.0;
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Ipopt::Index n, const Ipopt::Number* z, const Ipopt::Number*,
                         const Ipopt::Number*, Ipopt::Index, const Ipopt::Number*, const Ipopt::Number*, Ipopt::Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solution.assign(z, z + n);
  }

 private:
  const std::vector<double> start_;
};

}  // namespace cranesim
