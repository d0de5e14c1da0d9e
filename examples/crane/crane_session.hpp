// The crane behind a plain C++ interface without templates: built once (10 boom modes, the
// stroke drive), then stepped, read and destroyed. The C interface (c_api/) wraps it, so that
// engines in C or other languages link a compiled crane; its implementation lives in the unit
// crane_session.cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace crane {

/// What a session is built from (the crane program's flags of the same names).
struct SessionOptions {
  double payload_kg = 100.0;
  double step_s = 1e-3;
  double submodel_density = 1.0;
  /// The work cycle: time (s) and stroke offset (m) rows; empty: the synthetic cycle.
  std::vector<double> cycle_time, cycle_stroke;
};

class Session {
 public:
  /// What step() reports.
  enum class Step { ok, cycle_over, failed };

  /// The crane program's defaults.
  static SessionOptions default_options();
  /// Builds the crane: precomputation, static equilibrium, consistent initial conditions. Null
  /// with `error` set if that fails (a stroke outside the cylinder names its row).
  static std::unique_ptr<Session> create(const SessionOptions& o, std::string& error);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// One step of the work cycle, then the stresses and the damage meter. Allocates nothing.
  /// At the end of the cycle it does nothing and reports cycle_over; after a failure, failed
  /// (error() says why), and the state stays at the last good step.
  Step step();
  double time() const;
  double cycle_end() const;
  /// The stress read-outs (Pa) at the last step, in the order of output_names().
  const std::vector<double>& stresses() const;
  const std::vector<std::string>& output_names() const;
  /// Index of the IIW hot spot at the weld toe's centre in stresses().
  int hot_spot_index() const;
  /// Miner damage of the rainflow cycles closed so far, and with the residue closed as a
  /// repeating cycle (the damage per work cycle once the cycle is over).
  double damage_closed() const;
  double damage_per_cycle() const;
  const std::string& error() const;

 private:
  struct Impl;
  explicit Session(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace crane
