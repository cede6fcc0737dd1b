// The driver: read a parameter file, pick the space dimension, run.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include "convergence_study.h"
#include "parameters.h"
#include "viscoplastic_contact.h"

#include <filesystem>
#include <fstream>
#include <iostream>

namespace
{
  void
  print_usage(std::ostream &out)
  {
    out << "Usage: viscoplastic_contact FILE.prm\n"
        << "       viscoplastic_contact --print-parameters [FILE.prm]\n"
        << "       viscoplastic_contact --help\n\n"
        << "Solves the quasistatic contact problem of a viscoplastic body with "
           "a\nnonmonotone normal compliance law (../shared/design/model.md) "
           "for the\nscene FILE.prm describes. --print-parameters writes a "
           "complete, documented\nparameter file with the default values (the "
           "reference benchmark) to\nstandard output or to FILE.prm. The "
           "default scene is parameters/default.prm.\n";
  }
} // namespace



int
main(int argc, char **argv)
{
  using namespace dealii;
  using namespace ViscoContact;

  try
    {
      Utilities::MPI::MPI_InitFinalize mpi_initialization(argc, argv, 1);

      const std::string first = (argc > 1 ? argv[1] : "");
      if (first == "--help" || first == "-h")
        {
          print_usage(std::cout);
          return 0;
        }
      if (first == "--print-parameters")
        {
          ParameterHandler prm;
          Parameters::AllParameters::declare_parameters(prm);
          if (argc > 2)
            {
              std::ofstream out(argv[2]);
              prm.print_parameters(out, ParameterHandler::PRM);
            }
          else
            prm.print_parameters(std::cout, ParameterHandler::PRM);
          return 0;
        }
      if (argc != 2)
        {
          print_usage(std::cerr);
          return 1;
        }

      AssertThrow(std::filesystem::is_regular_file(first),
                  ExcMessage("The parameter file <" + first
                             + "> does not exist or is not a regular file."));
      AssertThrow(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1,
                  ExcMessage("This version of viscoplastic_contact runs on "
                             "one MPI rank; start it without mpirun."));

      ParameterHandler prm;
      Parameters::AllParameters::declare_parameters(prm);
      prm.parse_input(first);
      Parameters::AllParameters parameters;
      parameters.parse_parameters(prm);

      if (parameters.study_enabled && parameters.dimension == 2)
        ConvergenceStudy<2>(parameters).run();
      else if (parameters.study_enabled)
        ConvergenceStudy<3>(parameters).run();
      else if (parameters.dimension == 2)
        ViscoplasticContact<2>(parameters).run();
      else
        ViscoplasticContact<3>(parameters).run();
    }
  catch (ExceptionBase &exc)
    {
      // deal.II's exceptions: only the message, which names the parameter,
      // its value and what is accepted; where in the code is of no use here.
      std::cerr << "\n----------------------------------------------------\n"
                << "Error:\n";
      exc.print_info(std::cerr);
      std::cerr << "Aborting.\n"
                << "----------------------------------------------------"
                << std::endl;
      return 1;
    }
  catch (std::exception &exc)
    {
      std::cerr << "\n----------------------------------------------------\n"
                << "Error: " << exc.what() << "Aborting.\n"
                << "----------------------------------------------------"
                << std::endl;
      return 1;
    }
  catch (...)
    {
      std::cerr << "\nUnknown exception. Aborting." << std::endl;
      return 1;
    }
  return 0;
}
