// Pinocchio timing of the chain models of shared/reference-models.md, for comparison with
// autosim's `cargo run --release --example perf`.
//
// Builds chain-spatial-n and chain-planar-n, checks forward dynamics against the SymPy
// reference samples (shared/reference/<model>.json), then times one "derivatives" call
//   tau = -k q - c v;  ddq = FD(q, v, tau);  xdot = [v; ddq]
// at 512 random states (q uniform in [-pi, pi], v uniform in [-2, 2]), 201 timed rounds over
// all states, median ns per call; repeated `--reps` times (repetition is the outer loop over all
// cases), the minimum of the medians reported.
//
// Algorithms:
//   aba           pinocchio::aba (articulated-body algorithm, O(n), LOCAL convention)
//   crba-chol     pinocchio::crba + pinocchio::nonLinearEffects + pinocchio::cholesky
//                 (mass matrix, bias forces, sparse-aware Cholesky solve: the M ddq = f
//                 formulation autosim uses)
//
// Usage: chain_aba [--ref-dir DIR] [--reps R] [--build LABEL] [--check-only]
// Output (stdout): one JSON line per check ("check": ...) and per timing ("ns_per_call": ...).
// Exit status 1 if any check fails.

#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/cholesky.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/multibody.hpp> // Model, Data (Pinocchio 4 layout)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using pinocchio::Data;
using pinocchio::Model;
using Eigen::VectorXd;

namespace {

constexpr double kStiff = 2.0;   // k, N m/rad
constexpr double kDamp = 0.1;    // c, N m s/rad
constexpr double kGrav = 9.81;   // g, m/s^2
constexpr double kProd = 0.0005; // P, kg m^2 (spatial only)

struct Link {
  double m, L, Ixx, Iyy, Izz;
};

// Parameters of link i (1-based) exactly as reference-models.md defines them.
Link link_params(int i, bool spatial) {
  Link p;
  p.m = 1.0 + 0.1 * (i % 5);
  p.L = 0.4 + 0.05 * (i % 3);
  p.Ixx = p.m * p.L * p.L / 12.0;
  p.Iyy = p.m * p.L * p.L / 12.0 + 0.001;
  p.Izz = spatial ? 0.002 + 0.0001 * i : 0.002;
  return p;
}

std::string model_name(int n, bool spatial) {
  return std::string(spatial ? "chain-spatial-" : "chain-planar-") + std::to_string(n);
}

Model build_chain(int n, bool spatial) {
  Model model;
  model.gravity.linear(Eigen::Vector3d(0.0, 0.0, -kGrav));
  model.gravity.angular().setZero();
  pinocchio::JointIndex parent = 0; // universe = N
  double prev_L = 0.0;
  for (int i = 1; i <= n; ++i) {
    const Link p = link_params(i, spatial);
    // Joint point of Bi: N's origin for i = 1, else (0, 0, -L_(i-1)) in B(i-1) axes;
    // nominal orientation identical to the parent's.
    pinocchio::SE3 placement = pinocchio::SE3::Identity();
    if (i >= 2)
      placement.translation() = Eigen::Vector3d(0.0, 0.0, -prev_L);
    // Rotation about the parent's axis a_i = ((i-1) mod 3) + 1 (spatial) or axis 1 (planar).
    // For a single revolute joint the axis is the same in parent and child frames.
    const int axis = spatial ? (i - 1) % 3 : 0;
    pinocchio::JointModel jm;
    if (axis == 0)
      jm = pinocchio::JointModelRX();
    else if (axis == 1)
      jm = pinocchio::JointModelRY();
    else
      jm = pinocchio::JointModelRZ();
    parent = model.addJoint(parent, jm, placement, "joint" + std::to_string(i));
    // Pinocchio's Inertia(mass, lever, I_c): I_c is the rotational inertia matrix about the
    // mass center in body axes, I_c = sum_jk I_jk b_j b_k -- the matrix of the inertia dyadic,
    // which is what the reference lists (off-diagonal entries are dyadic components, i.e.
    // minus the products of inertia). So the reference matrix is used as is.
    Eigen::Matrix3d Ic;
    const double P = spatial ? kProd : 0.0;
    Ic << p.Ixx, P, 0.0, //
        P, p.Iyy, 0.0,   //
        0.0, 0.0, p.Izz;
    const pinocchio::Inertia Y(p.m, Eigen::Vector3d(0.0, 0.0, -p.L / 2.0),
                               pinocchio::Symmetric3(Ic));
    model.appendBodyToJoint(parent, Y, pinocchio::SE3::Identity());
    prev_L = p.L;
  }
  return model;
}

// ---------------------------------------------------------------------------------------------
// The timed "derivatives" calls. All write xdot = [v; ddq].

// With PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION (the `lib` build) the arguments are passed as
// Eigen::Ref<const VectorXd>, the type Pinocchio's precompiled library instantiates (and its
// Python bindings use), so aba, crba and nonLinearEffects run the library's code. Header-only
// builds pass the vectors as they are, as C++ users of the templates would (one trial run with
// the Ref wrapping in all builds looked ~10-15 % slower on the smallest models; not pursued).
#ifdef PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION
using CRef = Eigen::Ref<const VectorXd>;
#else
inline const VectorXd &CRef(const VectorXd &x) { return x; }
#endif

inline void torque(const VectorXd &q, const VectorXd &v, VectorXd &tau) {
  tau.noalias() = -kStiff * q - kDamp * v;
}

// What each forward-dynamics call below holds: the model, its data and a
// torque buffer.
struct CallState {
  const Model &model;
  Data &data;
  VectorXd tau;
  CallState(const Model &m, Data &d) : model(m), data(d), tau(m.nv) {}
  // Sets tau for (q, v); the number of speeds.
  int begin(const VectorXd &q, const VectorXd &v) {
    torque(q, v, tau);
    return model.nv;
  }
};

struct AbaCall : CallState {
  using CallState::CallState;
  static const char *name() { return "aba"; }
  void operator()(const VectorXd &q, const VectorXd &v, VectorXd &xdot) {
    const int n = begin(q, v);
    pinocchio::aba(model, data, CRef(q), CRef(v), CRef(tau));
    xdot.head(n) = v;
    xdot.tail(n) = data.ddq;
  }
};

struct CrbaCholCall : CallState {
  using CallState::CallState;
  static const char *name() { return "crba-chol"; }
  void operator()(const VectorXd &q, const VectorXd &v, VectorXd &xdot) {
    const int n = begin(q, v);
    pinocchio::crba(model, data, CRef(q));                     // upper triangle of M(q)
    pinocchio::nonLinearEffects(model, data, CRef(q), CRef(v)); // b(q, v) = C(q, v) v + g(q)
    pinocchio::cholesky::decompose(model, data);    // M = U D U^T
    xdot.head(n) = v;
    auto ddq = xdot.tail(n);
    ddq = tau - data.nle;
    pinocchio::cholesky::solve(model, data, ddq); // ddq = M^-1 (tau - b)
  }
};

// ---------------------------------------------------------------------------------------------
// Minimal reading of the reference JSON: the "samples" array's "q", "u", "du" arrays and
// named scalars in "parameters".

bool read_file(const std::string &path, std::string &out) {
  std::ifstream f(path);
  if (!f)
    return false;
  std::stringstream ss;
  ss << f.rdbuf();
  out = ss.str();
  return true;
}

// Parses the number array following `key` (e.g. "\"q\":") at or after pos; advances pos.
bool parse_array(const std::string &s, const std::string &key, size_t &pos,
                 std::vector<double> &out) {
  size_t k = s.find(key, pos);
  if (k == std::string::npos)
    return false;
  size_t b = s.find('[', k + key.size());
  size_t e = s.find(']', b);
  if (b == std::string::npos || e == std::string::npos)
    return false;
  out.clear();
  const char *p = s.c_str() + b + 1;
  const char *end = s.c_str() + e;
  while (p < end) {
    char *next = nullptr;
    double x = std::strtod(p, &next);
    if (next == p) {
      ++p; // skip ',', whitespace
      continue;
    }
    out.push_back(x);
    p = next;
  }
  pos = e + 1;
  return true;
}

bool parse_scalar(const std::string &s, size_t from, const std::string &name, double &x) {
  const std::string key = "\"" + name + "\":";
  size_t k = s.find(key, from);
  if (k == std::string::npos)
    return false;
  x = std::strtod(s.c_str() + k + key.size(), nullptr);
  return true;
}

struct Sample {
  std::vector<double> q, u, du;
};

bool read_samples(const std::string &s, std::vector<Sample> &out) {
  size_t pos = s.find("\"samples\"");
  if (pos == std::string::npos)
    return false;
  for (;;) {
    Sample smp;
    size_t p = pos;
    if (!parse_array(s, "\"q\":", p, smp.q))
      break;
    if (!parse_array(s, "\"u\":", p, smp.u) || !parse_array(s, "\"du\":", p, smp.du))
      return false;
    out.push_back(smp);
    pos = p;
  }
  return !out.empty();
}

// Checks parameters and every sample of <ref_dir>/<model>.json with both algorithms.
// Returns false on failure; true (and prints a "skipped" line) if the file is missing.
bool check_model(const std::string &ref_dir, int n, bool spatial, const std::string &build) {
  const std::string name = model_name(n, spatial);
  const std::string path = ref_dir + "/" + name + ".json";
  std::string text;
  if (!read_file(path, text)) {
    std::printf("{\"check\": \"%s\", \"status\": \"skipped (no %s)\"}\n", name.c_str(),
                path.c_str());
    return true;
  }
  // Parameters in the file must equal the ones computed here from the definition.
  const size_t params = text.find("\"parameters\":");
  double max_param_diff = 0.0;
  bool params_ok = params != std::string::npos;
  auto cmp = [&](const std::string &key, double mine) {
    double x;
    if (!parse_scalar(text, params, key, x)) {
      params_ok = false;
      return;
    }
    max_param_diff = std::max(max_param_diff, std::abs(x - mine) / std::max(1.0, std::abs(x)));
  };
  for (int i = 1; params_ok && i <= n; ++i) {
    const Link p = link_params(i, spatial);
    const std::string si = std::to_string(i);
    cmp("m" + si, p.m);
    cmp("L" + si, p.L);
    cmp("Ixx" + si, p.Ixx);
    cmp("Iyy" + si, p.Iyy);
    cmp("Izz" + si, p.Izz);
  }
  if (params_ok) {
    cmp("k", kStiff);
    cmp("c", kDamp);
    cmp("g", kGrav);
    if (spatial)
      cmp("P", kProd);
  }
  params_ok = params_ok && max_param_diff <= 1e-15;

  std::vector<Sample> samples;
  if (!read_samples(text, samples)) {
    std::printf("{\"check\": \"%s\", \"status\": \"FAIL: cannot parse %s\"}\n", name.c_str(),
                path.c_str());
    return false;
  }
  const Model model = build_chain(n, spatial);
  bool all_ok = params_ok;
  for (int alg = 0; alg < 2; ++alg) {
    Data data(model);
    AbaCall aba(model, data);
    CrbaCholCall crba(model, data);
    double worst = 0.0;
    bool shape_ok = true;
    VectorXd xdot(2 * n);
    for (const Sample &smp : samples) {
      if ((int)smp.q.size() != n || (int)smp.u.size() != n || (int)smp.du.size() != n) {
        shape_ok = false;
        break;
      }
      const VectorXd q = Eigen::Map<const VectorXd>(smp.q.data(), n);
      const VectorXd v = Eigen::Map<const VectorXd>(smp.u.data(), n);
      const VectorXd du = Eigen::Map<const VectorXd>(smp.du.data(), n);
      if (alg == 0)
        aba(q, v, xdot);
      else
        crba(q, v, xdot);
      // Relative to the sample's largest |du| (shared/reference/README.md).
      const double rel = (xdot.tail(n) - du).cwiseAbs().maxCoeff() / du.cwiseAbs().maxCoeff();
      worst = std::max(worst, rel);
    }
    const bool ok = shape_ok && params_ok && worst <= 1e-9;
    all_ok = all_ok && ok;
    std::printf("{\"check\": \"%s\", \"algorithm\": \"%s\", \"build\": \"%s\", "
                "\"samples\": %zu, \"max_rel_err_du\": %.3e, \"tolerance\": 1e-9, "
                "\"params_max_rel_diff\": %.1e, \"status\": \"%s\"}\n",
                name.c_str(), alg == 0 ? AbaCall::name() : CrbaCholCall::name(), build.c_str(),
                samples.size(), worst, max_param_diff, ok ? "pass" : "FAIL");
  }
  std::fflush(stdout);
  return all_ok;
}

// ---------------------------------------------------------------------------------------------
// Timing.

// Same generator as examples/perf.rs (xorshift, 53-bit uniform).
struct Rng {
  uint64_t s;
  double uniform(double lo, double hi) {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return lo + (hi - lo) * ((double)(s >> 11) / (double)(1ull << 53));
  }
};

template <class T> inline void do_not_optimize(T const &value) {
  asm volatile("" : : "r,m"(value) : "memory");
}

template <class Call>
double median_ns(Call &call, const std::vector<VectorXd> &qs, const std::vector<VectorXd> &vs,
                 VectorXd &xdot, int rounds) {
  const size_t count = qs.size();
  for (int w = 0; w < 20; ++w) // warm up
    for (size_t s = 0; s < count; ++s) {
      call(qs[s], vs[s], xdot);
      do_not_optimize(xdot.data());
    }
  std::vector<double> per_call(rounds);
  for (int r = 0; r < rounds; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t s = 0; s < count; ++s) {
      call(qs[s], vs[s], xdot);
      do_not_optimize(xdot.data());
    }
    const auto t1 = std::chrono::steady_clock::now();
    per_call[r] = std::chrono::duration<double, std::nano>(t1 - t0).count() / (double)count;
  }
  std::sort(per_call.begin(), per_call.end());
  return per_call[rounds / 2];
}

// One timed case: model, data, call and its fixed set of random states.
struct Timed {
  virtual ~Timed() = default;
  virtual double measure() = 0;
  std::string model;
  int n_states = 0;
  std::string algorithm;
  std::vector<double> medians;
};

template <class Call> struct TimedCase : Timed {
  Model pin_model;
  Data data;
  Call call;
  std::vector<VectorXd> qs, vs;
  VectorXd xdot;
  TimedCase(int n, bool spatial, Rng &rng)
      : pin_model(build_chain(n, spatial)), data(pin_model), call(pin_model, data),
        xdot(2 * n) {
    model = model_name(n, spatial);
    n_states = 2 * n;
    algorithm = Call::name();
    const size_t count = 512;
    qs.assign(count, VectorXd(n));
    vs.assign(count, VectorXd(n));
    for (size_t s = 0; s < count; ++s) {
      for (int i = 0; i < n; ++i)
        qs[s][i] = rng.uniform(-M_PI, M_PI);
      for (int i = 0; i < n; ++i)
        vs[s][i] = rng.uniform(-2.0, 2.0);
    }
  }
  double measure() override { return median_ns(call, qs, vs, xdot, 201); }
};

} // namespace

int main(int argc, char **argv) {
  std::string ref_dir = "/work/shared/reference";
  std::string build = "unspecified";
  int reps = 3;
  bool check_only = false;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--ref-dir" && a + 1 < argc)
      ref_dir = argv[++a];
    else if (arg == "--reps" && a + 1 < argc)
      reps = std::max(1, std::atoi(argv[++a]));
    else if (arg == "--build" && a + 1 < argc)
      build = argv[++a];
    else if (arg == "--check-only")
      check_only = true;
    else {
      std::fprintf(stderr,
                   "usage: %s [--ref-dir DIR] [--reps R] [--build LABEL] [--check-only]\n",
                   argv[0]);
      return 2;
    }
  }

  // Correctness first: every reference file present for the chains (at least n = 10).
  bool ok = true;
  for (bool spatial : {true, false})
    for (int n : {1, 2, 3, 5, 10})
      ok = check_model(ref_dir, n, spatial, build) && ok;
  if (!ok) {
    std::fprintf(stderr, "correctness check FAILED; not timing\n");
    return 1;
  }
  if (check_only)
    return 0;

  Rng rng{0x2545f4914f6cdd1dull};
  struct Case {
    int n;
    bool spatial;
  };
  const Case cases[] = {{1, true},  {2, true},  {3, true},  {5, true},
                        {7, true},  {10, true}, {20, true}, {10, false}};
  std::vector<std::unique_ptr<Timed>> timed;
  for (const Case &c : cases) {
    timed.emplace_back(new TimedCase<AbaCall>(c.n, c.spatial, rng));
    timed.emplace_back(new TimedCase<CrbaCholCall>(c.n, c.spatial, rng));
  }
  // Repetitions are the outer loop, so the repeats of one case are spread over the whole run
  // (a burst of load from other jobs then spoils at most one of them).
  for (int r = 0; r < reps; ++r)
    for (auto &t : timed)
      t->medians.push_back(t->measure());
  for (auto &t : timed) {
    const double best = *std::min_element(t->medians.begin(), t->medians.end());
    std::string list;
    for (size_t r = 0; r < t->medians.size(); ++r) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%s%.1f", r ? ", " : "", t->medians[r]);
      list += buf;
    }
    std::printf("{\"model\": \"%s\", \"n_states\": %d, \"ns_per_call\": %.1f, "
                "\"algorithm\": \"%s\", \"build\": \"%s\", \"medians\": [%s]}\n",
                t->model.c_str(), t->n_states, best, t->algorithm.c_str(), build.c_str(),
                list.c_str());
  }
  return 0;
}
