// Pinocchio (C++, from the PyPI wheel `pin`) timed on the robot arms of
// `tests/data/robots/` for `examples/robots.rs`: ABA (forward dynamics), CRBA alone, CRBA +
// nonlinear effects + Cholesky solve, RNEA (inverse dynamics). One thread, each figure the
// median of 7 rounds of 200,000 calls at one fixed random state (seed 0). Prints one line
// per model: name nv aba_ns crba_ns crba_solve_ns rnea_ns.
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/cholesky.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/joint-configuration.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <fstream>
#include <sstream>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

using namespace pinocchio;

static double median(std::vector<double> v) { std::sort(v.begin(), v.end()); return v[v.size() / 2]; }

template <class F> static double time_ns(F f, int calls) {
  std::vector<double> rounds;
  for (int r = 0; r < 7; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < calls; ++i) f();
    auto t1 = std::chrono::steady_clock::now();
    rounds.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / calls);
  }
  return median(rounds);
}

// The planar N-link chain of the project's benches: unit point masses at the ends of
// massless unit rods, revolute joints about z, gravity along -y (the inertia of a point
// mass about its own centre is zero).
static Model chain(int n) {
  Model m;
  m.gravity.linear(Eigen::Vector3d(0, -9.81, 0));
  JointIndex parent = 0;
  for (int i = 0; i < n; ++i) {
    SE3 placement = SE3::Identity();
    if (i > 0) placement.translation() = Eigen::Vector3d(0, -1.0, 0);
    parent = m.addJoint(parent, JointModelRZ(), placement, "j" + std::to_string(i));
    m.appendBodyToJoint(parent, Inertia(1.0, Eigen::Vector3d(0, -1.0, 0), Eigen::Matrix3d::Zero()), SE3::Identity());
  }
  return m;
}

// A model written by dump_model.py: per joint "TYPE parent R(9) t(3) mass c(3) Ixx Ixy Ixz Iyy Iyz Izz".
static Model from_dump(const std::string& path) {
  Model m;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string kind;
    s >> kind;
    if (kind == "gravity") { Eigen::Vector3d g; s >> g[0] >> g[1] >> g[2]; m.gravity.linear(g); continue; }
    int parent; Eigen::Matrix3d R; Eigen::Vector3d t, c; double mass, xx, xy, xz, yy, yz, zz;
    s >> parent;
    for (int r = 0; r < 3; ++r) for (int k = 0; k < 3; ++k) s >> R(r, k);
    s >> t[0] >> t[1] >> t[2] >> mass >> c[0] >> c[1] >> c[2] >> xx >> xy >> xz >> yy >> yz >> zz;
    Eigen::Matrix3d I; I << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    SE3 placement(R, t);
    JointIndex j;
    if (kind == "RX") j = m.addJoint(parent, JointModelRX(), placement, "j");
    else if (kind == "RY") j = m.addJoint(parent, JointModelRY(), placement, "j");
    else if (kind == "RZ") j = m.addJoint(parent, JointModelRZ(), placement, "j");
    else if (kind == "PX") j = m.addJoint(parent, JointModelPX(), placement, "j");
    else if (kind == "PY") j = m.addJoint(parent, JointModelPY(), placement, "j");
    else if (kind == "PZ") j = m.addJoint(parent, JointModelPZ(), placement, "j");
    else if (kind == "FreeFlyer") j = m.addJoint(parent, JointModelFreeFlyer(), placement, "j");
    else if (kind == "RevoluteUnaligned" || kind == "PrismaticUnaligned") {
      Eigen::Vector3d axis;
      s >> axis[0] >> axis[1] >> axis[2];
      if (kind == "RevoluteUnaligned") j = m.addJoint(parent, JointModelRevoluteUnaligned(axis), placement, "j");
      else j = m.addJoint(parent, JointModelPrismaticUnaligned(axis), placement, "j");
    }
    else { std::fprintf(stderr, "joint type %s not handled\n", kind.c_str()); std::exit(1); }
    m.appendBodyToJoint(j, Inertia(mass, c, I), SE3::Identity());
  }
  return m;
}

// One figure per algorithm: ABA, CRBA alone (M formed, upper triangle), CRBA + nonlinear
// effects + Cholesky solve (q'' through M), RNEA; each the median of 7 rounds.
static void run(const std::string& name, Model& m, int calls) {
  Data d(m);
  std::srand(0);
  Eigen::VectorXd q = neutral(m) + 0.3 * Eigen::VectorXd::Random(m.nq);
  Eigen::VectorXd v = Eigen::VectorXd::Random(m.nv), tau = Eigen::VectorXd::Zero(m.nv);
  double aba_ns = time_ns([&] { aba(m, d, q, v, tau); }, calls);
  double crba_ns = time_ns([&] { crba(m, d, q, Convention::WORLD); }, calls);
  Eigen::VectorXd a(m.nv);
  double crba_solve_ns = time_ns([&] {
    crba(m, d, q, Convention::WORLD);
    nonLinearEffects(m, d, q, v);
    cholesky::decompose(m, d);
    a = tau - d.nle;
    cholesky::solve(m, d, a);
  }, calls);
  double rnea_ns = time_ns([&] { rnea(m, d, q, v, a); }, calls);
  std::printf("%s nv %d aba_ns %.1f crba_ns %.1f crba_solve_ns %.1f rnea_ns %.1f\n", name.c_str(), (int)m.nv, aba_ns,
              crba_ns, crba_solve_ns, rnea_ns);
}

// Arguments: NAME DUMP [NAME DUMP ...], the dumps written by dump_model.py; a NAME
// starting with `chain` takes the number of links instead of a dump.
int main(int argc, char** argv) {
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string name = argv[i];
    if (name.rfind("chain", 0) == 0) {
      Model m = chain(std::stoi(argv[i + 1]));
      run(name, m, 20000);
      continue;
    }
    Model m = from_dump(argv[i + 1]);
    run(name, m, 200000);
  }
}
