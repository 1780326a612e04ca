// modelid command line: dispatches to the commands (fit, predict, simulate, export, check; one
// source file each) and turns their errors into messages and exit codes: 0 success, 1 bad input or
// data, 2 bad usage, 3 internal error.

#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>

#include "modelgen/data/data_error.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/model/error.hpp"
#include "runtime/cli/arguments.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/progress.hpp"
#include "runtime/cli/version.hpp"

namespace {

using namespace modelgen;
using namespace modelgen::internal;

constexpr const char* kUsage =
    "usage: modelid fit --robot ROBOT --data A.csv [--data B.csv ...] --method ols|wls|pim-wls\n"
    "                   [-o EST.json] [--truth TRUE.json] [--essential [--r-sigma R]]\n"
    "                   [--physical [--prior-weight W]] [--min-speed V[,...]] [--plot DIR]\n"
    "       modelid fit --method iv|didim --controller C.yaml --robot ROBOT --data A.csv\n"
    "                   [-o EST.json] [--truth TRUE.json] [--physical] [--plot DIR]\n"
    "       modelid fit --method pm [--fir-lags M] --robot ROBOT --data A.csv\n"
    "                   [-o EST.json] [--truth TRUE.json] [--physical] [--min-speed V[,...]]\n"
    "                   [--plot DIR]\n"
    "       modelid fit --method ml-eiv --periodic --robot ROBOT --data A.csv\n"
    "                   [-o EST.json] [--truth TRUE.json] [--physical] [--plot DIR]\n"
    "       modelid fit --method ml --approach 1|2|3|all --robot DESCRIPTION.yaml --periodic\n"
    "                   --data A.csv [--unknown load,Rv,Rc,Rz] [--known KNOWN.json]\n"
    "                   [--truth TRUTH.json] [--physical [--prior-weight W]] [-o EST.json]\n"
    "       modelid predict --robot ROBOT --params EST.json --data A.csv [--data B.csv ...]\n"
    "                   [-o PRED.csv] [--plot DIR]\n"
    "       modelid simulate --robot ROBOT [--params TRUE.json] --trajectory TRAJ.yaml\n"
    "                   --noise SIGMA[,SIGMA2,...] [--seed N] [--sample-time S] [--periods K]\n"
    "                   [--ignore-limits] -o A.csv\n"
    "       modelid simulate --robot DESCRIPTION.yaml --drive THETA.json --trajectory TRAJ.yaml\n"
    "                   --noise SIGMA[,SIGMA2,...] [--seed N] [--sample-time S] [--periods K]\n"
    "                   -o A.csv\n"
    "       modelid simulate --robot ROBOT [--params TRUE.json] --trajectory REF.yaml\n"
    "                   --controller C.yaml [--noise-q S] [--noise-tau S]\n"
    "                   [--encoder-resolution R] [--substeps N] [--seed N] [--periods K] -o A.csv\n"
    "       modelid validate --robot ROBOT --params EST.json --controller C.yaml --data A.csv\n"
    "                   [--plot DIR]\n"
    "       modelid export --robot DESCRIPTION --params EST.json -o IDENTIFIED\n"
    "       modelid check ROBOT\n"
    "       modelid check-trajectory --robot ROBOT --trajectory TRAJ.yaml\n"
    "                   [--ddq-limit A[,A2,..]] [--plot DIR]\n"
    "       modelid design --robot ROBOT --period T --harmonics N [--axes 1,2,..]\n"
    "                   [--hold q1=V,..] [--criterion cond|logdet] [--margin 0.95]\n"
    "                   [--starts K] [--seed S] [--noise SIGMA] [--samples S]\n"
    "                   [--ddq-limit A[,A2,..]] [--max-evaluations N] [--compare T.yaml]\n"
    "                   [--plot DIR] -o TRAJ.yaml\n"
    "       (any command: --progress shows progress lines also when stderr is not a terminal)\n"
    "       modelid --version | --help\n"
    "\n"
    "C.yaml: {type: pid, sample_time: S, kp: [..], ki: [..], kd: [..]}, one gain per joint; a\n"
    "closed-loop record has columns t, q, tau (the command) and qr (the reference).\n"
    "simulate refuses a trajectory beyond the description's joint limits (checked at 1 kHz or\n"
    "finer over one period) unless --ignore-limits; check-trajectory prints each limit's use\n"
    "(and the a-priori torques against effort limits when the description has link inertials);\n"
    "--plot DIR writes DIR/trajectory.svg (q, dq, ddq per joint against the limits).\n"
    "ROBOT is a description (.yaml/.urdf, through the numeric reference) or the name of a\n"
    "compiled-in generated model (tx40, kr150, ur5, iiwa14, panda, kuka_kr150_2,\n"
    "panda_arm, comau_smart_six). --angle-tolerance RAD (every command) reads a description\n"
    "as modelgen does (rounded quarter turns within RAD taken as exact; default 1e-4, 0: as\n"
    "written).\n"
    "Data files: CSV with a header t, q1..qn, tau1..taun and optionally dq1.., ddq1.. (without\n"
    "them, velocities and accelerations come from central differences). README.md has details.\n"
    "simulate --drive: THETA.json is {\"name\": value} over the drive model's parameters\n"
    "(XXj..Mj, JMj, Rvj, Rcj, Rzj, load_m, load_cx, ..., load_Iyz; missing: 0, Rzj 1); the\n"
    "noise (one sigma or one per motor) is added to the motor torques, tau = K^T tau_M written.\n"
    "export: the \"standard\" set of an estimate of fit --physical written into the description\n"
    "(DESCRIPTION.urdf -> IDENTIFIED.urdf, DESCRIPTION.yaml -> IDENTIFIED.yaml). URDF: each\n"
    "moving link's <inertial> gets its identified body less the a-priori inertials of the links\n"
    "fixed to it, which keep theirs (when that is no physical body, the moving link takes it all\n"
    "and the fixed links' inertials are removed, with a warning); drive parameters have no URDF\n"
    "element and go into a comment. YAML: every standard parameter as its known: section.\n";

int dispatch(int argc, char** argv) {
  const std::string command = argv[1];
  // --progress, for every command: progress lines also when stderr is not a terminal.
  int kept = 2;
  for (int a = 2; a < argc; ++a) {
    if (std::strcmp(argv[a], "--progress") == 0) {
      show_progress_in_logs(true);
    } else {
      argv[kept++] = argv[a];
    }
  }
  argc = kept;
  if (command == "fit") return run_fit(parse_arguments(argc, argv, kFitOptions));
  if (command == "predict") return run_predict(parse_arguments(argc, argv, kPredictOptions));
  if (command == "simulate") return run_simulate(parse_arguments(argc, argv, kSimulateOptions));
  if (command == "validate") return run_validate(parse_arguments(argc, argv, kValidateOptions));
  if (command == "export") return run_export(parse_arguments(argc, argv, kExportOptions));
  if (command == "design") return run_design(parse_arguments(argc, argv, kDesignOptions));
  if (command == "check-trajectory") {
    return run_check_trajectory(parse_arguments(argc, argv, kCheckTrajectoryOptions));
  }
  if (command == "check") {
    return run_check(parse_arguments(argc, argv, {{"--angle-tolerance", OptionKind::kOnce}}));
  }
  throw UsageError{"unknown command '" + command + "'"};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    (argc < 2 ? std::cerr : std::cout) << kUsage;
    return argc < 2 ? 2 : 0;
  }
  if (argc == 2 && std::strcmp(argv[1], "--version") == 0) {
    std::cout << "modelid " << kModelidVersion << "\n";
    return 0;
  }
  try {
    return dispatch(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "modelid: " << e.what() << "\n\n" << kUsage;
    return 2;
  } catch (const modelgen::InputError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const DataError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const EstimationError& e) {
    std::cerr << "modelid: cannot identify: " << e.what() << "\n";
    return 1;
  } catch (const std::invalid_argument& e) {
    std::cerr << "modelid: " << e.what() << "\n";
    return 1;
  } catch (const std::runtime_error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "modelid: internal error: " << e.what() << "; please report this\n";
    return 3;
  }
}
