// The C interface (flexstress_crane.h) over crane::Session. Nothing throws across it: every
// C++ exception becomes a null crane with its message, and the step path does not throw.
#include "flexstress_crane.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "../crane_session.hpp"

struct fs_crane {
  std::unique_ptr<crane::Session> session;
};

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void copy_error(const std::string& message, char* error, size_t size) {
  if (error == nullptr || size == 0) return;
  const size_t n = std::min(message.size(), size - 1);
  std::memcpy(error, message.data(), n);
  error[n] = '\0';
}

// The options' checks, naming the field (the same limits as the crane program's flags).
std::string check(const fs_crane_options& o) {
  const auto bad = [](const char* field, double value, const char* rule) {
    return std::string("fs_crane_options.") + field + " = " + std::to_string(value) + ": must be " +
           rule;
  };
  if (!(o.payload_kg >= 0 && std::isfinite(o.payload_kg)))
    return bad("payload_kg", o.payload_kg, "finite and >= 0");
  if (!(o.step_s > 0 && o.step_s <= 0.05)) return bad("step_s", o.step_s, "in (0, 0.05]");
  if (!(o.submodel_density > 0 && std::isfinite(o.submodel_density)))
    return bad("submodel_density", o.submodel_density, "finite and > 0");
  if (o.cycle_points < 0 || o.cycle_points == 1)
    return "fs_crane_options.cycle_points = " + std::to_string(o.cycle_points) +
           ": must be 0 (the synthetic cycle) or at least 2";
  if (o.cycle_points > 0 && (o.cycle_time == nullptr || o.cycle_stroke == nullptr))
    return "fs_crane_options: cycle_points = " + std::to_string(o.cycle_points) +
           " but cycle_time or cycle_stroke is null";
  return {};
}

}  // namespace

extern "C" {

void fs_crane_default_options(fs_crane_options* options) {
  if (options == nullptr) return;
  const crane::SessionOptions defaults = crane::Session::default_options();
  options->payload_kg = defaults.payload_kg;
  options->step_s = defaults.step_s;
  options->submodel_density = defaults.submodel_density;
  options->cycle_time = nullptr;
  options->cycle_stroke = nullptr;
  options->cycle_points = 0;
}

fs_crane* fs_crane_create(const fs_crane_options* options, char* error, size_t error_size) {
  copy_error("", error, error_size);
  try {
    if (options == nullptr) {
      copy_error("fs_crane_create: options is null (fs_crane_default_options fills them)", error,
                 error_size);
      return nullptr;
    }
    if (const std::string bad = check(*options); !bad.empty()) {
      copy_error(bad, error, error_size);
      return nullptr;
    }
    crane::SessionOptions o;
    o.payload_kg = options->payload_kg;
    o.step_s = options->step_s;
    o.submodel_density = options->submodel_density;
    if (options->cycle_points > 0) {
      o.cycle_time.assign(options->cycle_time, options->cycle_time + options->cycle_points);
      o.cycle_stroke.assign(options->cycle_stroke, options->cycle_stroke + options->cycle_points);
    }
    std::string why;
    auto session = crane::Session::create(o, why);
    if (!session) {
      copy_error("fs_crane_create: " + why, error, error_size);
      return nullptr;
    }
    return new fs_crane{std::move(session)};
  } catch (const std::exception& e) {
    copy_error(std::string("fs_crane_create: ") + e.what(), error, error_size);
  } catch (...) {
    copy_error("fs_crane_create: unknown failure", error, error_size);
  }
  return nullptr;
}

void fs_crane_destroy(fs_crane* crane) {
  delete crane;
}

int fs_crane_step(fs_crane* crane) {
  if (crane == nullptr) return FS_CRANE_NULL;
  switch (crane->session->step()) {
    case crane::Session::Step::ok: return FS_CRANE_OK;
    case crane::Session::Step::cycle_over: return FS_CRANE_CYCLE_OVER;
    case crane::Session::Step::failed: break;
  }
  return FS_CRANE_FAILED;
}

double fs_crane_time(const fs_crane* crane) {
  return crane != nullptr ? crane->session->time() : kNaN;
}
double fs_crane_cycle_end(const fs_crane* crane) {
  return crane != nullptr ? crane->session->cycle_end() : kNaN;
}

int fs_crane_num_outputs(const fs_crane* crane) {
  return crane != nullptr ? static_cast<int>(crane->session->stresses().size()) : 0;
}
const char* fs_crane_output_name(const fs_crane* crane, int index) {
  if (crane == nullptr || index < 0 || index >= fs_crane_num_outputs(crane)) return nullptr;
  return crane->session->output_names()[static_cast<size_t>(index)].c_str();
}
int fs_crane_stresses(const fs_crane* crane, double* out, int capacity) {
  if (crane == nullptr || out == nullptr || capacity <= 0) return 0;
  const auto& s = crane->session->stresses();
  const int n = std::min(capacity, static_cast<int>(s.size()));
  std::memcpy(out, s.data(), static_cast<size_t>(n) * sizeof(double));
  return n;
}
double fs_crane_hot_spot(const fs_crane* crane) {
  if (crane == nullptr) return kNaN;
  return crane->session->stresses()[static_cast<size_t>(crane->session->hot_spot_index())];
}

double fs_crane_damage_closed(const fs_crane* crane) {
  return crane != nullptr ? crane->session->damage_closed() : kNaN;
}
double fs_crane_damage_per_cycle(const fs_crane* crane) {
  return crane != nullptr ? crane->session->damage_per_cycle() : kNaN;
}

const char* fs_crane_error(const fs_crane* crane) {
  return crane != nullptr ? crane->session->error().c_str() : "fs_crane: null crane";
}

}  // extern "C"
