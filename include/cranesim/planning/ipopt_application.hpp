#pragma once
// The Ipopt application both of crane-opt's NLPs start from (the QR trajectory, the minimum-time
// collocation), and Ipopt's return status as a user reads it.

#include <IpIpoptApplication.hpp>

#include <string>

namespace cranesim {

struct IpoptSettings {
  int print_level = 0;
  double tolerance = 1e-8;
  int max_iterations = 3000;
};

/// An initialised Ipopt application: no banner, the settings, the adaptive barrier strategy; no
/// ipopt.opt read from the working directory. Throws std::runtime_error when it cannot start.
/// Problem-specific options may be set on it after.
Ipopt::SmartPtr<Ipopt::IpoptApplication> ipoptApplication(const IpoptSettings& settings);

/// "maximum iterations exceeded", …
std::string ipoptStatusInWords(Ipopt::ApplicationReturnStatus status);

}  // namespace cranesim
