// Scheduler signals (stop_signals.h): the handler records the first signal
// and restores the default action, so that a second signal stops the
// program at once.

#include "robustness/stop_signals.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <csignal>
#include <cstdlib>
#include <string>
#include <iostream>
#include <unistd.h>

namespace ViscoContact
{
  namespace StopSignals
  {
    namespace
    {
      // Written by the handler, read by the time loop: sig_atomic_t is what
      // a handler may write safely.
      volatile std::sig_atomic_t first_signal = 0;

      // Set once by install(): whether this process is a rank that Open
      // MPI's mpirun started, and whether it is rank 0 of the job.
      bool started_by_mpirun = false;
      bool first_rank        = true;

      extern "C" void
      record_signal(const int signal)
      {
        if (first_signal == 0)
          first_signal = signal;
        // Said at once (write() may be called in a handler, a stream may
        // not), so that the log shows that the signal was taken. Open MPI's
        // mpirun passes a SIGTERM or SIGINT sent to it on to every rank as
        // SIGTERM and kills the ranks right after: then the run cannot
        // finish its step. Which process sent the signal cannot be told
        // reliably here (a library may call this handler without the
        // signal's siginfo), so under mpirun rank 0 says both.
        if (started_by_mpirun && signal != SIGUSR1)
          {
            const char note[]
              = "\nSignal received. If it was sent to mpirun, Open MPI ends "
                "the job at once (mpirun passes SIGTERM and SIGINT on to the "
                "ranks as SIGTERM and kills them right after): the current "
                "time step is not finished and no checkpoint is written. To "
                "stop a run with a checkpoint, send SIGUSR1 to mpirun "
                "(scancel --signal=USR1, #SBATCH --signal=USR1@300), or start "
                "the ranks with srun. Sent to the ranks, it stops the run at "
                "the end of the current time step, which then says where it "
                "stopped and whether a checkpoint was written.\n";
            if (first_rank)
              (void)!::write(STDERR_FILENO, note, sizeof(note) - 1);
          }
        else
          {
            const char note[]
              = "\nSignal received: the run stops at the end of the current "
                "time step (or phase of the set-up) and then says where it "
                "stopped and whether a checkpoint was written; a second "
                "signal stops it at once.\n";
            (void)!::write(STDERR_FILENO, note, sizeof(note) - 1);
          }
        // The next signal of any of the three kinds takes its default
        // action: the process ends at once. (signal() may be called in a
        // handler, POSIX lists it as async-signal-safe.)
        for (const int s : {SIGTERM, SIGINT, SIGUSR1})
          std::signal(s, SIG_DFL);
      }
    } // namespace



    void
    install()
    {
      // SA_RESTART: system calls that the signal interrupts (file writes,
      // MPI's polling) continue instead of failing with EINTR.
      const char *rank = std::getenv("OMPI_COMM_WORLD_RANK");
      started_by_mpirun
        = (rank != nullptr && std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr);
      first_rank              = (rank == nullptr || std::string(rank) == "0");
      struct sigaction action = {};
      action.sa_handler       = record_signal;
      sigemptyset(&action.sa_mask);
      action.sa_flags = SA_RESTART;
      for (const int signal : {SIGTERM, SIGINT, SIGUSR1})
        sigaction(signal, &action, nullptr);
      // A write beyond a file size limit (ulimit -f, a batch system's limit)
      // raises SIGXFSZ, whose default action kills the process with a core
      // dump. Ignored, the write fails with EFBIG instead, and the run stops
      // like on a full disk: with the file's name and "File too large".
      std::signal(SIGXFSZ, SIG_IGN);
    }



    int
    received()
    {
      return first_signal;
    }



    void
    stop_if_received(const MPI_Comm communicator, const std::string &phase)
    {
      const int signal
        = dealii::Utilities::MPI::max(int(first_signal), communicator);
      if (signal == 0)
        return;
      if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
        std::cout << "Stopped during the set-up (" << phase << ") on "
                  << name(signal)
                  << "; no time step was computed, and nothing is saved."
                  << std::endl;
      throw Stopped{signal};
    }



    std::string
    name(const int signal)
    {
      switch (signal)
        {
          case SIGTERM:
            return "SIGTERM";
          case SIGINT:
            return "SIGINT";
          case SIGUSR1:
            return "SIGUSR1";
          default:
            return "signal " + std::to_string(signal);
        }
    }
  } // namespace StopSignals
} // namespace ViscoContact
