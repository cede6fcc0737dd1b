// Scheduler signals (stop_signals.h): the handler records the first signal
// and restores the default action, so that a second signal stops the
// program at once.

#include "robustness/stop_signals.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <csignal>
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

      extern "C" void
      record_signal(const int signal)
      {
        if (first_signal == 0)
          first_signal = signal;
        // Said at once (write() may be called in a handler, a stream may
        // not), so that the log shows that the signal was taken.
        const char note[]
          = "\nSignal received: the run stops after the current time step, "
            "with a checkpoint (during the set-up: after its current phase, "
            "without one); a second signal stops it at once.\n";
        (void)!::write(STDERR_FILENO, note, sizeof(note) - 1);
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
