// Pinocchio's side of the project's benchmark comparison (run by compare.sh).
//
//   timing [--min-rep-ms MS] [--reps R] [--warmup-ms MS] [--group all|dynamics|kinematics]
//          [--frames FRAMES.json] MODEL.json ...
//
// Each file is in the layout of tests/data/pinocchio/*.json: a `model` section (joints in
// tree order with their placement in the parent frame, bodies with mass, mass centre and
// inertia about it in the joint frame, gravity) and `samples` (q, v, a, tau, and outputs to
// check against). For each file the program
//   1. builds the Pinocchio model from the `model` section (axis-aligned joints become
//      JointModelRX/RY/RZ, PX/PY/PZ, as Pinocchio's URDF parser makes them);
//   2. checks rnea, crba, nonLinearEffects, computeGeneralizedGravity, aba,
//      computeCoriolisMatrix and the energies against the outputs stored in the samples,
//      and stops with an error if they disagree (then it would not be the same model);
//   3. prints an FNV-1a fingerprint of the states' bits (q, v, a, tau per sample), which
//      compare.sh matches against the Rust benchmark's, so both time the same numbers;
//   4. times each algorithm of the group (--group: dynamics, kinematics or all, the
//      default): one call per state, the states taken in turn, in repetitions of N calls
//      (N chosen so a repetition lasts at least --min-rep-ms), and prints the median over
//      --reps repetitions, with the fastest and slowest.
// Dynamics: rnea, crba and aba (both in Pinocchio's LOCAL convention, the default, and in
// WORLD; compare.sh compares against the faster one), nonLinearEffects,
// computeGeneralizedGravity, computeCoriolisMatrix.
// Kinematics: forwardKinematics(q), forwardKinematics(q, v, a), computeJointJacobians (alone
// and with getJointJacobian for every joint), computeJointJacobiansTimeVariation, centerOfMass(q), jacobianCenterOfMass(q),
// ccrba(q, v), dccrba(q, v), and, for a model with operational frames, three frame
// algorithms: forwardKinematics(q) + updateFramePlacements; computeJointJacobians +
// getFrameJacobian(LOCAL_WORLD_ALIGNED) for each frame; forwardKinematics(q, v, 0) +
// getFrameClassicalAcceleration(LOCAL_WORLD_ALIGNED) for each frame. Derivatives (same
// group): computeRNEADerivatives(q, v, a), computeABADerivatives(q, v, tau), computeMinverse.
//
// Frames: --frames names a file (frames.json beside this program) that lists, per model
// name, the URDF link each joint moves and the links hung on fixed joints. The frame
// algorithms run on a copy of the model with the frames Pinocchio's URDF parser would make
// from that (a JOINT and a BODY frame per joint, a FIXED_JOINT and a BODY frame per fixed
// link); the frames they read are every BODY frame whose parent frame is a FIXED_JOINT
// one. A model without an entry (the quadruped) has none: its frame algorithms are
// skipped. The dynamics and the other kinematics run on the model without frames.
//
// Output, one record a line, tab-separated:
//   model    <name> <nq> <nv>
//   states   <name> <count> <fingerprint, 16 hex digits>
//   check    <name> <worst relative error>
//   frames   <name> <count> <comma-separated frame names>
//   time     <name> <algorithm> <median ns> <min ns> <max ns> <calls per repetition>

#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>
#include <pinocchio/algorithm/center-of-mass.hpp>
#include <pinocchio/algorithm/centroidal.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/energy.hpp>
#include <pinocchio/algorithm/frames.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/rnea-derivatives.hpp>
#include <pinocchio/math.hpp>
#include <pinocchio/multibody.hpp>

#include <boost/json/src.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace json = boost::json;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using Model = pinocchio::Model;
using Data = pinocchio::Data;

namespace {

// ---- reading the file -------------------------------------------------------------------

json::value load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  json::parse_options options;
  options.numbers = json::number_precision::precise;  // correctly rounded, like Rust's
  return json::parse(text.str(), {}, options);
}

double number(const json::value& x) { return x.to_number<double>(); }

VectorXd vector(const json::value& x) {
  const json::array& a = x.as_array();
  VectorXd out(static_cast<Eigen::Index>(a.size()));
  for (std::size_t i = 0; i < a.size(); ++i) out[Eigen::Index(i)] = number(a[i]);
  return out;
}

MatrixXd matrix(const json::value& x) {
  const json::array& rows = x.as_array();
  const std::size_t n = rows.size(), m = n ? rows[0].as_array().size() : 0;
  MatrixXd out(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
  for (std::size_t i = 0; i < n; ++i) {
    const json::array& row = rows[i].as_array();
    if (row.size() != m) throw std::runtime_error("ragged matrix");
    for (std::size_t j = 0; j < m; ++j) out(Eigen::Index(i), Eigen::Index(j)) = number(row[j]);
  }
  return out;
}

Eigen::Vector3d vector3(const json::value& x) {
  const VectorXd v = vector(x);
  if (v.size() != 3) throw std::runtime_error("expected 3 numbers");
  return v;
}

// ---- the model --------------------------------------------------------------------------

// Pinocchio's joint model for a joint of the file; the name, to check against the file's
// `pinocchio_type` when it has one.
std::string joint_model_name(const std::string& type, const Eigen::Vector3d& axis) {
  const char* letter = axis == Eigen::Vector3d::UnitX()   ? "X"
                       : axis == Eigen::Vector3d::UnitY() ? "Y"
                       : axis == Eigen::Vector3d::UnitZ() ? "Z"
                                                          : nullptr;
  if (type == "revolute") return letter ? std::string("JointModelR") + letter : "JointModelRevoluteUnaligned";
  if (type == "prismatic") return letter ? std::string("JointModelP") + letter : "JointModelPrismaticUnaligned";
  if (type == "free_flyer") return "JointModelFreeFlyer";
  throw std::runtime_error("unsupported joint type " + type);
}

Model build_model(const json::object& m) {
  Model model;
  const json::array& joints = m.at("joints").as_array();
  const json::array& bodies = m.at("bodies").as_array();
  if (joints.size() != bodies.size()) throw std::runtime_error("one body per joint expected");
  std::vector<std::pair<Eigen::Index, double>> armature;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const json::object& j = joints[i].as_object();
    const std::string type(j.at("type").as_string());
    const std::string name(j.at("name").as_string());
    const Eigen::Vector3d axis = j.at("axis").is_null() ? Eigen::Vector3d::Zero() : vector3(j.at("axis"));
    const std::string kind = joint_model_name(type, axis);
    if (const json::value* stated = j.if_contains("pinocchio_type"))
      if (std::string(stated->as_string()) != kind)
        throw std::runtime_error("joint " + name + ": file says " + std::string(stated->as_string()) + ", axis gives " + kind);
    const json::object& p = j.at("placement").as_object();
    const pinocchio::SE3 placement(Eigen::Matrix3d(matrix(p.at("rotation"))), vector3(p.at("translation")));
    const auto parent = pinocchio::JointIndex(j.at("parent").to_number<long>() + 1);  // 0 = world
    pinocchio::JointIndex id;
    if (kind == "JointModelRX") id = model.addJoint(parent, pinocchio::JointModelRX(), placement, name);
    else if (kind == "JointModelRY") id = model.addJoint(parent, pinocchio::JointModelRY(), placement, name);
    else if (kind == "JointModelRZ") id = model.addJoint(parent, pinocchio::JointModelRZ(), placement, name);
    else if (kind == "JointModelPX") id = model.addJoint(parent, pinocchio::JointModelPX(), placement, name);
    else if (kind == "JointModelPY") id = model.addJoint(parent, pinocchio::JointModelPY(), placement, name);
    else if (kind == "JointModelPZ") id = model.addJoint(parent, pinocchio::JointModelPZ(), placement, name);
    else if (kind == "JointModelRevoluteUnaligned")
      id = model.addJoint(parent, pinocchio::JointModelRevoluteUnaligned(axis), placement, name);
    else if (kind == "JointModelPrismaticUnaligned")
      id = model.addJoint(parent, pinocchio::JointModelPrismaticUnaligned(axis), placement, name);
    else id = model.addJoint(parent, pinocchio::JointModelFreeFlyer(), placement, name);
    if (const json::value* d = j.if_contains("damping"))
      if (number(*d) != 0.0)
        throw std::runtime_error("joint " + name + " has damping: nonLinearEffects would not be the bias");
    if (const json::value* a = j.if_contains("armature"))
      if (number(*a) != 0.0) armature.emplace_back(model.joints[id].idx_v(), number(*a));
    const json::object& b = bodies[i].as_object();
    if (b.at("joint").to_number<std::size_t>() != i) throw std::runtime_error("body order differs from joint order");
    model.appendBodyToJoint(id,
                            pinocchio::Inertia(number(b.at("mass")), vector3(b.at("com")),
                                               Eigen::Matrix3d(matrix(b.at("inertia_com")))),
                            pinocchio::SE3::Identity());
  }
  for (const auto& [index, value] : armature) model.armature[index] = value;
  model.gravity.linear(vector3(m.at("gravity")));
  if (model.nq != m.at("nq").to_number<int>() || model.nv != m.at("nv").to_number<int>())
    throw std::runtime_error("nq/nv differ from the file's");
  return model;
}

// ---- the states -------------------------------------------------------------------------

struct States {
  std::vector<VectorXd> q, v, a, tau;
  std::size_t size() const { return q.size(); }
};

States read_states(const json::array& samples, const Model& model) {
  States s;
  for (const json::value& x : samples) {
    const json::object& o = x.as_object();
    s.q.push_back(vector(o.at("q")));
    s.v.push_back(vector(o.at("v")));
    s.a.push_back(vector(o.at("a")));
    s.tau.push_back(vector(o.at("tau")));
    if (s.q.back().size() != model.nq || s.v.back().size() != model.nv || s.a.back().size() != model.nv ||
        s.tau.back().size() != model.nv)
      throw std::runtime_error("a sample's sizes differ from the model's");
  }
  if (s.size() == 0) throw std::runtime_error("no samples");
  return s;
}

// FNV-1a over the little-endian bytes of every number, sample by sample: q, v, a, tau.
std::uint64_t fingerprint(const States& s) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  auto add = [&hash](const VectorXd& x) {
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      std::uint64_t bits;
      const double value = x[i];
      std::memcpy(&bits, &value, sizeof bits);
      for (int byte = 0; byte < 8; ++byte) hash = (hash ^ ((bits >> (8 * byte)) & 0xff)) * 0x100000001b3ull;
    }
  };
  for (std::size_t k = 0; k < s.size(); ++k) {
    add(s.q[k]);
    add(s.v[k]);
    add(s.a[k]);
    add(s.tau[k]);
  }
  return hash;
}

// ---- checking Pinocchio against the stored outputs ---------------------------------------

// max |got - want| / (1 + max |want|)
double relative_error(const MatrixXd& got, const MatrixXd& want) {
  if (got.rows() != want.rows() || got.cols() != want.cols()) return INFINITY;
  return (got - want).cwiseAbs().maxCoeff() / (1.0 + want.cwiseAbs().maxCoeff());
}

MatrixXd symmetric_from_upper(const MatrixXd& m) {
  MatrixXd s = m.triangularView<Eigen::Upper>();
  s.triangularView<Eigen::StrictlyLower>() = m.transpose().triangularView<Eigen::StrictlyLower>();
  return s;
}

double check(const Model& model, const json::array& samples, const States& s) {
  Data data(model);
  double worst = 0.0;
  auto compare = [&worst](const MatrixXd& got, const json::value* want, bool is_matrix) {
    if (!want) return;
    worst = std::max(worst, relative_error(got, is_matrix ? matrix(*want) : MatrixXd(vector(*want))));
  };
  for (std::size_t k = 0; k < s.size(); ++k) {
    const json::object& o = samples[k].as_object();
    const VectorXd &q = s.q[k], &v = s.v[k], &a = s.a[k], &tau = s.tau[k];
    compare(pinocchio::rnea(model, data, q, v, a), o.if_contains("rnea"), false);
    compare(pinocchio::nonLinearEffects(model, data, q, v), o.if_contains("nle"), false);
    compare(pinocchio::computeGeneralizedGravity(model, data, q), o.if_contains("gravity_torque"), false);
    compare(pinocchio::aba(model, data, q, v, tau), o.if_contains("aba"), false);
    compare(pinocchio::aba(model, data, q, v, tau, pinocchio::Convention::WORLD), o.if_contains("aba"), false);
    for (auto convention : {pinocchio::Convention::LOCAL, pinocchio::Convention::WORLD}) {
      const MatrixXd mass = symmetric_from_upper(pinocchio::crba(model, data, q, convention));
      compare(mass, o.if_contains("crba"), true);
      compare(mass * a, o.if_contains("crba_a"), false);
    }
    const MatrixXd coriolis = pinocchio::computeCoriolisMatrix(model, data, q, v);
    // C is not unique: compare C v, against the stored matrix or the stored product.
    if (const json::value* c = o.if_contains("coriolis"))
      worst = std::max(worst, relative_error(coriolis * v, matrix(*c) * v));
    compare(coriolis * v, o.if_contains("coriolis_v"), false);
    if (const json::value* e = o.if_contains("kinetic_energy"))
      worst = std::max(worst, std::abs(pinocchio::computeKineticEnergy(model, data, q, v) - number(*e)) / (1.0 + std::abs(number(*e))));
    if (const json::value* e = o.if_contains("potential_energy"))
      worst = std::max(worst, std::abs(pinocchio::computePotentialEnergy(model, data, q) - number(*e)) / (1.0 + std::abs(number(*e))));
  }
  return worst;
}

// ---- timing -----------------------------------------------------------------------------

// Keeps the compiler from dropping or hoisting the work on `p` (as Rust's black_box).
template <class T>
inline void escape(T* p) {
  asm volatile("" : : "g"(p) : "memory");
}

using Clock = std::chrono::steady_clock;

struct Timing {
  double median, min, max;
  long calls;
};

struct Settings {
  double min_rep_ms = 100.0;
  double warmup_ms = 200.0;
  int reps = 15;
  bool dynamics = true;
  bool kinematics = true;
};

// `call(k)` on state k; states taken in turn, one call per state.
template <class Call>
double run(Call& call, std::size_t n, long calls) {
  std::size_t k = 0;
  const auto start = Clock::now();
  for (long i = 0; i < calls; ++i) {
    call(k);
    if (++k == n) k = 0;
  }
  return std::chrono::duration<double, std::nano>(Clock::now() - start).count();
}

template <class Call>
Timing time_calls(Call call, std::size_t n, const Settings& settings) {
  // Warm up, and find how many calls fill a repetition.
  long calls = 64;
  double elapsed = 0.0;
  const auto warmup_end = Clock::now() + std::chrono::duration<double, std::milli>(settings.warmup_ms);
  while (true) {
    elapsed = run(call, n, calls);
    if (elapsed >= 1e6 * settings.min_rep_ms && Clock::now() >= warmup_end) break;
    if (elapsed < 1e6 * settings.min_rep_ms) calls *= 2;
  }
  std::vector<double> per_call;
  for (int r = 0; r < settings.reps; ++r) per_call.push_back(run(call, n, calls) / double(calls));
  std::sort(per_call.begin(), per_call.end());
  const std::size_t m = per_call.size();
  const double median = m % 2 ? per_call[m / 2] : 0.5 * (per_call[m / 2 - 1] + per_call[m / 2]);
  return {median, per_call.front(), per_call.back(), calls};
}

void report(const std::string& name, const char* algorithm, const Timing& t) {
  std::printf("time\t%s\t%s\t%.2f\t%.2f\t%.2f\t%ld\n", name.c_str(), algorithm, t.median, t.min, t.max, t.calls);
  std::fflush(stdout);
}

void time_model(const std::string& name, const Model& model, const States& s, const Settings& settings) {
  Data data(model);
  const std::size_t n = s.size();
  using pinocchio::Convention;
  report(name, "rnea", time_calls([&](std::size_t k) { escape(&pinocchio::rnea(model, data, s.q[k], s.v[k], s.a[k])); }, n, settings));
  report(name, "crba", time_calls([&](std::size_t k) { escape(&pinocchio::crba(model, data, s.q[k])); }, n, settings));
  report(name, "crba_world",
         time_calls([&](std::size_t k) { escape(&pinocchio::crba(model, data, s.q[k], Convention::WORLD)); }, n, settings));
  report(name, "nonLinearEffects",
         time_calls([&](std::size_t k) { escape(&pinocchio::nonLinearEffects(model, data, s.q[k], s.v[k])); }, n, settings));
  report(name, "computeGeneralizedGravity",
         time_calls([&](std::size_t k) { escape(&pinocchio::computeGeneralizedGravity(model, data, s.q[k])); }, n, settings));
  report(name, "aba", time_calls([&](std::size_t k) { escape(&pinocchio::aba(model, data, s.q[k], s.v[k], s.tau[k])); }, n, settings));
  report(name, "aba_world",
         time_calls([&](std::size_t k) { escape(&pinocchio::aba(model, data, s.q[k], s.v[k], s.tau[k], Convention::WORLD)); },
                    n, settings));
  report(name, "computeCoriolisMatrix",
         time_calls([&](std::size_t k) { escape(&pinocchio::computeCoriolisMatrix(model, data, s.q[k], s.v[k])); }, n, settings));
}

// ---- kinematics ---------------------------------------------------------------------------

// A copy of `model` with the frames Pinocchio's URDF parser would make, from the model's
// entry in the frames file: a JOINT frame and a BODY frame (the link it moves) per joint, a
// FIXED_JOINT frame and a BODY frame per link hung on a fixed joint, each placed as the
// parser places it (the parent link's frame composed with the fixed joint's origin).
Model with_frames(const Model& model, const json::object& entry) {
  Model framed = model;
  std::map<std::string, pinocchio::FrameIndex> link_frames;  // link name -> its BODY frame
  const json::object& links = entry.at("links").as_object();
  for (pinocchio::JointIndex j = 1; j < pinocchio::JointIndex(model.njoints); ++j) {
    const json::value* link = links.if_contains(model.names[j]);
    if (!link) throw std::runtime_error("frames: no link named for joint " + model.names[j]);
    const auto joint_frame = framed.addJointFrame(j);
    const std::string name(link->as_string());
    link_frames[name] = framed.addBodyFrame(name, j, pinocchio::SE3::Identity(), int(joint_frame));
  }
  for (const json::value& x : entry.at("fixed").as_array()) {
    const json::object& f = x.as_object();
    const std::string name(f.at("link").as_string()), parent(f.at("parent").as_string());
    const Eigen::Vector3d xyz = vector3(f.at("xyz")), rpy = vector3(f.at("rpy"));
    const pinocchio::SE3 origin(pinocchio::rpy::rpyToMatrix(rpy[0], rpy[1], rpy[2]), xyz);
    if (parent == "universe") {  // the URDF's root link
      link_frames[name] = framed.addFrame(pinocchio::Frame(name, 0, 0, origin, pinocchio::BODY));
      continue;
    }
    const auto found = link_frames.find(parent);
    if (found == link_frames.end()) throw std::runtime_error("frames: " + name + "'s parent " + parent + " is not listed before it");
    const pinocchio::Frame& up = framed.frames[found->second];
    const pinocchio::SE3 placement = up.placement * origin;
    const auto fixed = framed.addFrame(
        pinocchio::Frame(std::string(f.at("joint").as_string()), up.parentJoint, found->second, placement, pinocchio::FIXED_JOINT));
    link_frames[name] = framed.addFrame(pinocchio::Frame(name, up.parentJoint, fixed, placement, pinocchio::BODY));
  }
  return framed;
}

// The operational frames of a model: every BODY frame whose parent frame is a FIXED_JOINT.
std::vector<pinocchio::FrameIndex> operational_frames(const Model& model) {
  std::vector<pinocchio::FrameIndex> out;
  for (pinocchio::FrameIndex i = 0; i < pinocchio::FrameIndex(model.nframes); ++i) {
    const pinocchio::Frame& f = model.frames[i];
    if (i != 0 && f.type == pinocchio::BODY && model.frames[f.parentFrame].type == pinocchio::FIXED_JOINT) out.push_back(i);
  }
  return out;
}

void time_kinematics(const std::string& name, const Model& model, const States& s, const json::object* frames,
                     const Settings& settings) {
  Data data(model);
  const std::size_t n = s.size();
  report(name, "forwardKinematics_q", time_calls([&](std::size_t k) {
           pinocchio::forwardKinematics(model, data, s.q[k]);
           escape(&data.oMi);
         }, n, settings));
  report(name, "forwardKinematics_qva", time_calls([&](std::size_t k) {
           pinocchio::forwardKinematics(model, data, s.q[k], s.v[k], s.a[k]);
           escape(&data.oMi);
           escape(&data.v);
           escape(&data.a);
         }, n, settings));
  report(name, "computeJointJacobians",
         time_calls([&](std::size_t k) { escape(&pinocchio::computeJointJacobians(model, data, s.q[k])); }, n, settings));
  // Every joint's Jacobian as ours gives them (LOCAL_WORLD_ALIGNED, one 6 × nv matrix per
  // joint): computeJointJacobians then getJointJacobian for each joint.
  std::vector<MatrixXd> joint_jacobians(model.njoints, MatrixXd::Zero(6, model.nv));
  report(name, "computeJointJacobians_getJointJacobian", time_calls([&](std::size_t k) {
           pinocchio::computeJointJacobians(model, data, s.q[k]);
           for (pinocchio::JointIndex j = 1; j < pinocchio::JointIndex(model.njoints); ++j)
             pinocchio::getJointJacobian(model, data, j, pinocchio::LOCAL_WORLD_ALIGNED, joint_jacobians[j]);
           escape(joint_jacobians.data());
         }, n, settings));
  report(name, "computeJointJacobiansTimeVariation", time_calls([&](std::size_t k) {
           escape(&pinocchio::computeJointJacobiansTimeVariation(model, data, s.q[k], s.v[k]));
           escape(&data.J);
         }, n, settings));
  // What ours gives: every joint's Jacobian and its J̇ v (LOCAL_WORLD_ALIGNED), from
  // getJointJacobian and getJointJacobianTimeVariation for each joint.
  MatrixXd joint_rate = MatrixXd::Zero(6, model.nv);
  std::vector<VectorXd> joint_rates_v(model.njoints, VectorXd::Zero(6));
  report(name, "computeJointJacobiansTimeVariation_perJoint", time_calls([&](std::size_t k) {
           pinocchio::computeJointJacobiansTimeVariation(model, data, s.q[k], s.v[k]);
           for (pinocchio::JointIndex j = 1; j < pinocchio::JointIndex(model.njoints); ++j) {
             pinocchio::getJointJacobian(model, data, j, pinocchio::LOCAL_WORLD_ALIGNED, joint_jacobians[j]);
             pinocchio::getJointJacobianTimeVariation(model, data, j, pinocchio::LOCAL_WORLD_ALIGNED, joint_rate);
             joint_rates_v[j].noalias() = joint_rate * s.v[k];
           }
           escape(joint_jacobians.data());
           escape(joint_rates_v.data());
         }, n, settings));
  report(name, "centerOfMass", time_calls([&](std::size_t k) { escape(&pinocchio::centerOfMass(model, data, s.q[k])); }, n, settings));
  report(name, "jacobianCenterOfMass",
         time_calls([&](std::size_t k) { escape(&pinocchio::jacobianCenterOfMass(model, data, s.q[k])); }, n, settings));
  report(name, "ccrba", time_calls([&](std::size_t k) {
           escape(&pinocchio::ccrba(model, data, s.q[k], s.v[k]));
           escape(&data.hg);
         }, n, settings));
  report(name, "dccrba", time_calls([&](std::size_t k) {
           escape(&pinocchio::dccrba(model, data, s.q[k], s.v[k]));
           escape(&data.Ag);
           escape(&data.hg);
         }, n, settings));

  // The derivatives of the dynamics, and M⁻¹.
  MatrixXd dtau_dq = MatrixXd::Zero(model.nv, model.nv), dtau_dv = dtau_dq, dtau_da = dtau_dq;
  report(name, "computeRNEADerivatives", time_calls([&](std::size_t k) {
           pinocchio::computeRNEADerivatives(model, data, s.q[k], s.v[k], s.a[k], dtau_dq, dtau_dv, dtau_da);
           escape(&dtau_dq);
           escape(&dtau_dv);
         }, n, settings));
  MatrixXd ddq_dq = MatrixXd::Zero(model.nv, model.nv), ddq_dv = ddq_dq, ddq_dtau = ddq_dq;
  report(name, "computeABADerivatives", time_calls([&](std::size_t k) {
           pinocchio::computeABADerivatives(model, data, s.q[k], s.v[k], s.tau[k], ddq_dq, ddq_dv, ddq_dtau);
           escape(&ddq_dq);
           escape(&ddq_dv);
         }, n, settings));
  report(name, "computeMinverse", time_calls([&](std::size_t k) {
           escape(&pinocchio::computeMinverse(model, data, s.q[k]));
         }, n, settings));

  // The frame algorithms, on the model with its URDF's frames.
  const json::value* entry = frames ? frames->if_contains(name) : nullptr;
  if (!entry) {
    std::printf("frames\t%s\t0\t\n", name.c_str());
    std::fflush(stdout);
    return;
  }
  const Model framed = with_frames(model, entry->as_object());
  const std::vector<pinocchio::FrameIndex> ids = operational_frames(framed);
  std::string names;
  for (const auto i : ids) names += (names.empty() ? "" : ",") + framed.frames[i].name;
  std::printf("frames\t%s\t%zu\t%s\n", name.c_str(), ids.size(), names.c_str());
  std::fflush(stdout);
  if (ids.empty()) return;
  Data fdata(framed);
  // getFrameJacobian writes the columns of the frame's joint's support: the others stay
  // zero, as set here once.
  std::vector<MatrixXd> jacobians(ids.size(), MatrixXd::Zero(6, framed.nv));
  std::vector<pinocchio::Motion> accelerations(ids.size(), pinocchio::Motion::Zero());
  const VectorXd zero = VectorXd::Zero(framed.nv);
  using pinocchio::LOCAL_WORLD_ALIGNED;
  report(name, "framePlacements", time_calls([&](std::size_t k) {
           pinocchio::forwardKinematics(framed, fdata, s.q[k]);
           pinocchio::updateFramePlacements(framed, fdata);
           escape(&fdata.oMf);
         }, n, settings));
  report(name, "frameJacobians", time_calls([&](std::size_t k) {
           pinocchio::computeJointJacobians(framed, fdata, s.q[k]);
           for (std::size_t f = 0; f < ids.size(); ++f)
             pinocchio::getFrameJacobian(framed, fdata, ids[f], LOCAL_WORLD_ALIGNED, jacobians[f]);
           escape(jacobians.data());
         }, n, settings));
  report(name, "frameClassicalAccelerations", time_calls([&](std::size_t k) {
           pinocchio::forwardKinematics(framed, fdata, s.q[k], s.v[k], zero);
           for (std::size_t f = 0; f < ids.size(); ++f)
             accelerations[f] = pinocchio::getFrameClassicalAcceleration(framed, fdata, ids[f], LOCAL_WORLD_ALIGNED);
           escape(accelerations.data());
         }, n, settings));
}

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr,
               "timing: %s\nusage: timing [--min-rep-ms MS] [--reps R] [--warmup-ms MS] [--group all|dynamics|kinematics]\n"
               "              [--frames FRAMES.json] MODEL.json ...\n",
               why);
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  std::vector<std::string> files;
  std::string frames_path;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> double {
      if (i + 1 >= argc) usage((arg + " needs a value").c_str());
      return std::atof(argv[++i]);
    };
    if (arg == "--min-rep-ms") settings.min_rep_ms = value();
    else if (arg == "--reps") settings.reps = int(value());
    else if (arg == "--warmup-ms") settings.warmup_ms = value();
    else if (arg == "--group" || arg == "--frames") {
      if (i + 1 >= argc) usage((arg + " needs a value").c_str());
      const std::string given = argv[++i];
      if (arg == "--frames") frames_path = given;
      else if (given == "dynamics") settings.kinematics = false;
      else if (given == "kinematics") settings.dynamics = false;
      else if (given != "all") usage(("unknown group " + given).c_str());
    }
    else if (arg.rfind("--", 0) == 0) usage(("unknown option " + arg).c_str());
    else files.push_back(arg);
  }
  if (files.empty()) usage("no model file");
  if (settings.reps < 5) usage("--reps must be at least 5");
  json::value frames;
  if (!frames_path.empty()) {
    try {
      frames = load(frames_path);
      if (!frames.is_object()) throw std::runtime_error("not a JSON object");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "timing: %s: %s\n", frames_path.c_str(), e.what());
      return 1;
    }
  }
  std::printf("# Pinocchio %s, Eigen %d.%d.%d, EIGEN_MAX_ALIGN_BYTES %d; %d repetitions of >= %.0f ms, median\n",
              PINOCCHIO_VERSION, EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION, int(EIGEN_MAX_ALIGN_BYTES),
              settings.reps, settings.min_rep_ms);
  for (const std::string& path : files) {
    try {
      const json::value doc = load(path);
      const json::object& o = doc.as_object();
      const std::string name(o.at("name").as_string());
      const Model model = build_model(o.at("model").as_object());
      const json::array& samples = o.at("samples").as_array();
      const States states = read_states(samples, model);
      std::printf("model\t%s\t%d\t%d\n", name.c_str(), model.nq, model.nv);
      std::printf("states\t%s\t%zu\t%016llx\n", name.c_str(), states.size(),
                  static_cast<unsigned long long>(fingerprint(states)));
      const double error = check(model, samples, states);
      std::printf("check\t%s\t%.3g\n", name.c_str(), error);
      std::fflush(stdout);
      if (!(error < 1e-9)) {
        std::fprintf(stderr, "timing: %s: Pinocchio disagrees with the outputs stored in the file (%.3g): not the same model\n",
                     path.c_str(), error);
        return 1;
      }
      if (settings.dynamics) time_model(name, model, states, settings);
      if (settings.kinematics) time_kinematics(name, model, states, frames.if_object(), settings);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "timing: %s: %s\n", path.c_str(), e.what());
      return 1;
    }
  }
  return 0;
}
