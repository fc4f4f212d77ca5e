#include "profile_reader.hpp"

#include <fmt/format.h>

#include <numbers>

namespace cranesim {

namespace {

/// `{type: input, value, command: speed | value, order: 1 | 2, time_constant, limits: {speed,
/// acceleration, min, max}}`: a drive its caller commands while the model runs.
InputProfile readInput(const YamlField& f) {
  f.allowKeys({"type", "unit", "value", "command", "order", "time_constant", "limits"});
  InputProfile p;
  InputSpec& s = p.spec;
  s.value = f.at("value").number();
  if (const auto c = f.find("command")) s.command = c->choice({"speed", "value"}) == "speed" ? InputCommand::Speed : InputCommand::Value;
  if (const auto o = f.find("order")) {
    s.order = o->integer();
    if (s.order != 1 && s.order != 2) o->fail(fmt::format("an input's order is 1 or 2 (lags in series), found {}", s.order));
  }
  if (const auto tau = f.find("time_constant")) s.time_constant = tau->within(1e-4, 100.0, "s");
  if (const auto l = f.find("limits")) {
    l->allowKeys({"speed", "acceleration", "min", "max"});
    if (const auto v = l->find("speed")) s.max_speed = v->positive();
    if (const auto a = l->find("acceleration")) {
      if (s.command == InputCommand::Value)
        a->fail("an acceleration limit belongs to a speed command; a value command's drive is limited by limits.speed");
      s.max_acceleration = a->positive();
    }
    s.min = l->number("min", s.min);
    s.max = l->number("max", s.max);
    if (!(s.min < s.max)) l->fail(fmt::format("limits.min ({}) must lie below limits.max ({})", s.min, s.max));
    if (!(s.value >= s.min && s.value <= s.max))
      f.at("value").fail(fmt::format("the starting value {} lies outside limits [{}, {}]", s.value, s.min, s.max));
  }
  return p;
}

}  // namespace

Profile readProfile(const YamlField& f) {
  if (f.isScalar()) return Profile(ConstantProfile{f.number()});
  const std::string type =
      f.at("type").choice({"constant", "ramp", "trapezoid", "cosine_step", "cosine_full", "tanh", "table", "input"});
  double scale = 1.0;
  if (const auto unit = f.find("unit")) scale = unit->choice({"deg", "rad", "m"}) == "deg" ? std::numbers::pi / 180.0 : 1.0;
  if (type == "input") return Profile(readInput(f), scale);
  if (type == "constant") {
    f.allowKeys({"type", "unit", "value"});
    return Profile(ConstantProfile{f.at("value").number()}, scale);
  }
  if (type == "ramp") {
    f.allowKeys({"type", "unit", "value", "rate", "t_start"});
    return Profile(RampProfile{f.number("value", 0.0), f.at("rate").number(), f.number("t_start", 0.0)}, scale);
  }
  if (type == "trapezoid") {
    f.allowKeys({"type", "unit", "from", "distance", "t_start", "duration", "t_accel", "t_decel"});
    TrapezoidProfile p{f.number("from", 0.0), f.at("distance").number(), f.number("t_start", 0.0),
                       f.at("duration").positive(), f.at("t_accel").positive(), f.at("t_decel").positive()};
    if (p.t_accel + p.t_decel > p.duration)
      f.fail(fmt::format("t_accel + t_decel ({}) exceeds duration ({})", p.t_accel + p.t_decel, p.duration));
    return Profile(p, scale);
  }
  if (type == "cosine_step" || type == "tanh") {
    f.allowKeys({"type", "unit", "from", "to", "t_start", "t_end", "confidence", "lambda"});
    const double from = f.at("from").number(), to = f.at("to").number();
    const double t0 = f.at("t_start").number(), t1 = f.at("t_end").number();
    if (!(t1 > t0)) f.at("t_end").fail(fmt::format("t_end ({}) must be after t_start ({})", t1, t0));
    if (type == "cosine_step") {
      if (f.has("confidence") || f.has("lambda")) f.fail("only a tanh profile has a confidence or lambda");
      return Profile(CosineStepProfile{from, to, t0, t1}, scale);
    }
    // λ(c) = atanh(c) (E-13). Table E-1's printed λ differ from atanh(c) in the 3rd–4th digit
    // (2.6476 for 99 % where atanh gives 2.6467); `lambda:` takes a value as printed.
    if (f.has("lambda") && f.has("confidence")) f.at("lambda").fail("give either confidence or lambda, not both");
    if (f.has("lambda")) return Profile(TanhProfile{from, to, t0, t1, f.at("lambda").positive()}, scale);
    const double c = f.number("confidence", 0.99);
    if (!(c > 0.0 && c < 1.0)) f.at("confidence").fail(fmt::format("confidence must lie in (0, 1), found {}", c));
    return Profile(TanhProfile{from, to, t0, t1, tanhConfidenceCoefficient(c)}, scale);
  }
  if (type == "cosine_full") {
    f.allowKeys({"type", "unit", "base", "peak", "t_start", "t_end"});
    const double t0 = f.at("t_start").number(), t1 = f.at("t_end").number();
    if (!(t1 > t0)) f.at("t_end").fail(fmt::format("t_end ({}) must be after t_start ({})", t1, t0));
    return Profile(CosineFullProfile{f.number("base", 0.0), f.at("peak").number(), t0, t1}, scale);
  }
  f.allowKeys({"type", "unit", "t", "value", "interpolation", "end_slopes"});
  TableProfile p;
  if (const auto i = f.find("interpolation")) {
    const std::string kind = i->choice({"cubic", "linear", "step"});
    p.interpolation = kind == "cubic" ? Interpolation::Cubic : kind == "linear" ? Interpolation::Linear : Interpolation::Step;
    if (p.interpolation != Interpolation::Cubic && f.has("end_slopes"))
      f.at("end_slopes").fail(fmt::format("end slopes belong to a cubic table, not a {} one", kind));
  }
  p.t = f.at("t").numbers();
  p.y = f.at("value").numbers();
  if (p.t.size() < 2) f.at("t").fail("a table needs at least two points");
  if (p.t.size() != p.y.size())
    f.at("value").fail(fmt::format("has {} values for {} times", p.y.size(), p.t.size()));
  for (std::size_t k = 1; k < p.t.size(); ++k)
    if (!(p.t[k] > p.t[k - 1])) f.at("t").fail(fmt::format("times must increase strictly (entry {})", k));
  const bool zero_end_slopes = !f.has("end_slopes") || f.at("end_slopes").choice({"zero", "natural"}) == "zero";
  p.slopes = splineSlopes(p.t, p.y, zero_end_slopes);
  return Profile(p, scale);
}

}  // namespace cranesim
