#include "cranesim/planning/ipopt_application.hpp"

#include <stdexcept>

namespace cranesim {

Ipopt::SmartPtr<Ipopt::IpoptApplication> ipoptApplication(const IpoptSettings& settings) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> ipopt = IpoptApplicationFactory();
  auto& options = *ipopt->Options();
  options.SetStringValue("sb", "yes");
  options.SetIntegerValue("print_level", settings.print_level);
  options.SetNumericValue("tol", settings.tolerance);
  options.SetIntegerValue("max_iter", settings.max_iterations);
  options.SetStringValue("mu_strategy", "adaptive");
  // MUMPS left to choose its fill-reducing ordering takes SCOTCH for the lifts' KKT systems, and
  // SCOTCH's ordering is randomised: the same input factored with a different fill rounds
  // differently, and over 100 iterations that grew into plans differing by 0.4 m of hoist rope
  // (97 or 98 iterations, ±4.7 or ±4.85 cm of sway on the building lift) from run to run.
  // Approximate minimum degree is deterministic and, measured on the shipped minimum-time lifts,
  // no slower.
  options.SetIntegerValue("mumps_pivot_order", 0);
  const Ipopt::ApplicationReturnStatus status = ipopt->Initialize("");  // "": no ipopt.opt from the working directory
  if (status != Ipopt::Solve_Succeeded) throw std::runtime_error("Ipopt: " + ipoptStatusInWords(status));
  return ipopt;
}

std::string ipoptStatusInWords(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded: return "solve succeeded";
    case Ipopt::Solved_To_Acceptable_Level: return "solved to acceptable level";
    case Ipopt::Infeasible_Problem_Detected: return "infeasible problem detected";
    case Ipopt::Search_Direction_Becomes_Too_Small: return "search direction becomes too small";
    case Ipopt::Diverging_Iterates: return "diverging iterates";
    case Ipopt::User_Requested_Stop: return "user requested stop";
    case Ipopt::Feasible_Point_Found: return "feasible point found";
    case Ipopt::Maximum_Iterations_Exceeded: return "maximum iterations exceeded";
    case Ipopt::Restoration_Failed: return "restoration failed";
    case Ipopt::Error_In_Step_Computation: return "error in step computation";
    case Ipopt::Maximum_CpuTime_Exceeded: return "maximum CPU time exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom: return "not enough degrees of freedom";
    case Ipopt::Invalid_Problem_Definition: return "invalid problem definition";
    case Ipopt::Invalid_Option: return "invalid option";
    case Ipopt::Invalid_Number_Detected: return "invalid number detected";
    case Ipopt::Unrecoverable_Exception: return "unrecoverable exception";
    case Ipopt::NonIpopt_Exception_Thrown: return "non-Ipopt exception thrown";
    case Ipopt::Insufficient_Memory: return "insufficient memory";
    case Ipopt::Internal_Error: return "internal error";
  }
  return "unknown status " + std::to_string(static_cast<int>(status));
}

}  // namespace cranesim
