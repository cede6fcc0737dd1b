// The driver: read a parameter file, pick the space dimension, run.
//
// As in the deal.II tutorials, main() only reads the input, chooses between
// a single run and a convergence study and between 2D and 3D, and turns
// every error into a readable message. Everything else is in the classes it
// creates.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include "back_ends/blas_threads.h"
#include "studies/convergence_study.h"
#include "parameters.h"
#include "robustness/file_output.h"
#include "robustness/mpi_tools.h"
#include "robustness/output_folder.h"
#include "robustness/stop_signals.h"
#include "viscoplastic_contact.h"

#include <filesystem>
#include <fstream>
#include <cstdio>
#include <iostream>
#include <memory>
#include <regex>
#include <sstream>
#include <vector>

namespace
{
  using namespace dealii;
  using namespace ViscoContact;

  // The usage text of --help and of a wrong command line.
  void
  print_usage(std::ostream &out)
  {
    out
      << "Usage: viscoplastic_contact FILE.prm\n"
      << "       viscoplastic_contact --print-parameters [FILE.prm [--force]]\n"
      << "       viscoplastic_contact --help\n\n"
      << "Solves the quasistatic contact problem of a viscoplastic body with "
         "a\nnonmonotone normal compliance law for the scene FILE.prm "
         "describes, on\none MPI rank or many (mpirun -np N ...). The model "
         "and the scheme are\ndescribed in doc/model.md, the program in "
         "doc/algorithm.md.\n--print-parameters writes a complete, documented "
         "parameter file with the\ndefault values (the reference benchmark) "
         "to standard output or to FILE.prm;\nan existing FILE.prm is only "
         "replaced with --force.\nThe default scene is "
         "parameters/default.prm.\n";
  }

  // Two things a parameter file may not mean the way ParameterHandler reads
  // it: a file that sets nothing (empty, or only comments) runs the
  // reference benchmark into output/default; and a '#' inside the value of
  // a path entry starts a comment (ParameterHandler knows no escape for it),
  // so "results#2" becomes "results".
  void
  warn_about_parameter_file(const std::string &file)
  {
    std::ifstream    in(file);
    std::string      line;
    bool             sets_an_entry = false;
    unsigned int     number        = 0;
    const std::regex set_line("^\\s*set\\s");
    const std::regex path_entry(
      "^\\s*set\\s+(Output directory|Mesh file)\\s*=\\s*([^#]*[^#\\s])#.*");
    while (std::getline(in, line))
      {
        ++number;
        sets_an_entry = sets_an_entry || std::regex_search(line, set_line);
        std::smatch match;
        if (std::regex_match(line, match, path_entry))
          std::cerr << "Warning: line " << number << " of <" << file
                    << ">: the value of <" << match[1]
                    << "> ends at the '#' (a '#' starts a comment in a "
                       "parameter file and cannot be part of a value); the "
                       "run uses <"
                    << match[2] << ">." << std::endl;
      }
    if (!sets_an_entry)
      std::cerr << "Warning: the parameter file <" << file
                << "> sets no entry; every value is the default (the "
                   "reference benchmark, output into output/default)."
                << std::endl;
  }



  // --print-parameters [FILE [--force]] writes every entry with its
  // documentation and default value, to FILE or to standard output, and
  // returns the exit status. The command line never destroys a file: an
  // existing file (a scene the user wrote, say) is only replaced with
  // --force, and the new text goes to a temporary name first, so that a
  // failed write leaves the old file as it was.
  int
  print_parameters(const std::vector<std::string> &arguments)
  {
    bool                     force = false;
    std::vector<std::string> files;
    for (const std::string &argument : arguments)
      if (argument == "--force")
        force = true;
      else
        files.push_back(argument);
    if (files.size() > 1 || (force && files.empty()))
      {
        print_usage(std::cerr);
        return 1;
      }
    ParameterHandler          prm;
    Parameters::AllParameters defaults;
    defaults.add_parameters(prm);
    std::ostringstream text;
    prm.print_parameters(text, ParameterHandler::PRM);
    if (files.empty())
      {
        std::cout << text.str() << std::flush;
        return 0;
      }
    const std::string &file = files[0];
    std::error_code    error;
    if (std::filesystem::symlink_status(file, error).type()
          != std::filesystem::file_type::not_found
        && !force)
      {
        std::cerr << "Error: the file <" << file
                  << "> exists; --print-parameters does not overwrite "
                     "it. Choose another name, or add --force to "
                     "replace it."
                  << std::endl;
        return 1;
      }
    // Written without replacing anything unless --force: a file that
    // appears under the name meanwhile is not overwritten either.
    const std::string problem = FileOutput::write_file(file, text.str(), force);
    if (!problem.empty())
      {
        std::cerr << "Error: " << problem << std::endl;
        return 1;
      }
    return 0;
  }



  // The parameter file: every entry bound to its member, the file parsed
  // (unknown entries and values that do not match their pattern are errors
  // that name the entry), and the values checked (parameters.cc). A mesh
  // file is found relative to the parameter file that names it; settings
  // that depend on the number of ranks (CHOLMOD and UMFPACK need one rank)
  // are checked here, before any work.
  Parameters::AllParameters
  read_parameters(const std::string &file)
  {
    AssertThrow(std::filesystem::is_regular_file(file),
                ExcMessage("The parameter file <" + file
                           + "> does not exist or is not a regular file."));
    // The entries are bound to the members of parameters: parse_input()
    // fills them, check_parameters() checks them.
    ParameterHandler          prm;
    Parameters::AllParameters parameters;
    parameters.prescribed_displacements.resize(
      Parameters::count_numbered_subsections(file, "Prescribed displacement"));
    parameters.surface_loads.resize(
      Parameters::count_numbered_subsections(file, "Surface load"));
    parameters.further_materials.resize(
      std::max(2u, Parameters::count_numbered_subsections(file, "Material"))
      - 1);
    parameters.further_contact_zones.resize(
      std::max(2u, Parameters::count_numbered_subsections(file, "Contact zone"))
      - 1);
    parameters.add_parameters(prm);
    Parameters::parse_parameter_file(prm, file);
    // What the parameter file may not mean as ParameterHandler reads it is
    // allowed, but said (rank 0).
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      warn_about_parameter_file(file);
    parameters.check_parameters(prm);
    parameters.parameter_file = file;
    if (!parameters.mesh_file.empty()
        && std::filesystem::path(parameters.mesh_file).is_relative())
      parameters.mesh_file
        = (std::filesystem::path(file).parent_path() / parameters.mesh_file)
            .lexically_normal()
            .string();
    parameters.check_run_configuration(
      Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD));
    return parameters;
  }



  // The box around the message of an error that ends the run (the message
  // starts with its separator from "Error:").
  void
  report_error(const std::string &message)
  {
    std::cerr << "\n----------------------------------------------------\n"
              << "Error:" << message << "Aborting.\n"
              << "----------------------------------------------------"
              << std::endl;
  }
} // namespace



// @sect4{main}
//
// Three ways to call the program: --help, --print-parameters (a complete
// parameter file with the default values, i.e. the reference benchmark), or
// one parameter file to run.
int
main(int argc, char **argv)
{
  using namespace dealii;
  using namespace ViscoContact;

  // Outside the try block, so that MPI is still up when an error is
  // reported; with several ranks an error on one of them ends all of them.
  // The last argument lets deal.II share the cores of a node among its
  // ranks: each rank gets (cores / ranks on the node) threads, which the
  // stress update at the stress points uses (DEAL_II_NUM_THREADS limits
  // them further). Everything else is parallel through the MPI ranks.
  Utilities::MPI::MPI_InitFinalize
    mpi_initialization(argc, argv, numbers::invalid_unsigned_int);
  // Standard output is line buffered even when it goes into a file or a
  // pipe (a batch job's log): every progress line reaches the log when it
  // is complete, not when a buffer of several kB is full. std::cout writes
  // through C's stdout (synchronised with stdio), so this covers it too.
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  // The BLAS runs on one thread; the sparse factorisation gives it the
  // rank's threads for its dense kernels (blas_threads.h).
  set_blas_threads(1);
  // SIGTERM, SIGINT and SIGUSR1 stop the run after the current time step,
  // with a checkpoint (stop_signals.h). Installed once MPI is up: Open MPI's
  // start-up sets its own handlers.
  StopSignals::install();
  const bool several_ranks
    = (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1);
  // An error that every rank raised (most errors: the checks agree on
  // their outcome) ends all ranks in order, with the message printed by
  // rank 0. An error on some ranks only, while the others wait in a
  // collective call that will never complete, is found by a barrier that
  // does not complete within a few seconds: then MPI_Abort ends them all.
  // On one rank returning an error code is enough.
  const MPITools::ErrorAgreement error_agreement;
  const auto stop_all_ranks = [&](const std::string &message) {
    if (several_ranks && error_agreement.all_ranks_stopped(5.))
      {
        if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
          report_error(message);
        return 1;
      }
    report_error(message);
    if (several_ranks)
      {
        // MPI_Abort runs no destructors: the output folders' temporaries
        // and lock go first (not collective).
        OutputFolder::release_all();
        MPI_Abort(MPI_COMM_WORLD, 1);
      }
    return 1;
  };
  // The problem lives outside the try block: if an error reaches main()
  // on one rank only, that rank must not run the problem's destructors
  // before MPI_Abort, since some of them (MUMPS's, say) are collective calls
  // that the other ranks, busy elsewhere, would never join. MPI_Abort does
  // not return, so the objects are never destroyed then.
  std::unique_ptr<ViscoplasticContact<2>> problem_2d;
  std::unique_ptr<ViscoplasticContact<3>> problem_3d;
  try
    {
      // The options first: they need no parameter file.
      const std::string first = (argc > 1 ? argv[1] : "");
      if (first == "--help" || first == "-h")
        {
          print_usage(std::cout);
          return 0;
        }
      if (first == "--print-parameters")
        return print_parameters(
          std::vector<std::string>(argv + std::min(argc, 2), argv + argc));
      // Otherwise exactly one argument, the parameter file.
      if (argc != 2)
        {
          print_usage(std::cerr);
          return 1;
        }
      const Parameters::AllParameters parameters = read_parameters(first);

      // A convergence study or a single run, in the dimension the parameter
      // file asks for: both dimensions are compiled, the choice is made at
      // run time.
      if (parameters.study_enabled && parameters.dimension == 2)
        ConvergenceStudy<2>(parameters, MPI_COMM_WORLD).run();
      else if (parameters.study_enabled)
        ConvergenceStudy<3>(parameters, MPI_COMM_WORLD).run();
      else if (parameters.dimension == 2)
        {
          problem_2d = std::make_unique<ViscoplasticContact<2>>(parameters);
          problem_2d->run();
        }
      else
        {
          problem_3d = std::make_unique<ViscoplasticContact<3>>(parameters);
          problem_3d->run();
        }
    }
  catch (const StopSignals::Stopped &stopped)
    {
      // All ranks stopped after the same step, its checkpoint written: an
      // orderly end, with the status a shell gives a process killed by
      // the signal, so that job scripts see that the run is not complete.
      return 128 + stopped.signal;
    }
  catch (MPITools::ExcOnAllRanks &exc)
    {
      // An error that every rank has raised at the same point (a mesh that
      // a group root could not build): reported once, and every rank ends
      // in order.
      if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        {
          std::ostringstream message;
          exc.print_info(message);
          report_error("\n" + message.str());
        }
      return 1;
    }
  catch (ExceptionBase &exc)
    {
      // deal.II's exceptions: only the message, which names the parameter,
      // its value and what is accepted; where in the code is of no use here.
      std::ostringstream message;
      exc.print_info(message);
      return stop_all_ranks("\n" + message.str());
    }
  catch (std::exception &exc)
    {
      // Other exceptions (from the standard library, say) keep their own
      // text.
      return stop_all_ranks(std::string(" ") + exc.what() + "\n");
    }
  catch (...)
    {
      // Anything else: at least say that the run did not succeed.
      return stop_all_ranks(" an unknown exception.\n");
    }
  return 0;
}
