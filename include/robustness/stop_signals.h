#ifndef viscoplastic_contact_stop_signals_h
#define viscoplastic_contact_stop_signals_h

#include <deal.II/base/mpi.h>

#include <string>

namespace ViscoContact
{
  // @sect3{Scheduler signals}
  //
  // Batch schedulers send SIGTERM (Slurm, PBS), SIGINT or SIGUSR1 some time
  // before they kill a job. The program then finishes the current time step,
  // writes a checkpoint, says how to resume, and exits with status
  // 128 + the signal's number. A second signal stops it at once (the
  // default action of the signal).
  //
  // The handler only records the signal; the time loop asks once per step
  // and the set-up between its phases, and the ranks agree on the answer
  // with a maximum over the ranks, so that all stop at the same point even
  // if only one rank got the signal.
  namespace StopSignals
  {
    // Installs the handler for SIGTERM, SIGINT and SIGUSR1, and ignores
    // SIGXFSZ (a write beyond a file size limit then fails with EFBIG).
    void
    install();

    // The number of the first signal received, 0 if none.
    int
    received();

    // SIGTERM, SIGINT, SIGUSR1 (or "signal N").
    std::string
    name(const int signal);

    // Collective, between the phases of the set-up: if any rank has
    // received a signal, every rank says so (rank 0 prints where the run
    // stopped: phase) and throws Stopped. Nothing is saved: there is no
    // step to save yet.
    void
    stop_if_received(const MPI_Comm communicator, const std::string &phase);

    // Thrown by the time loop on every rank after the checkpoint of the
    // step at which it stopped (or by stop_if_received() during the
    // set-up); main() turns it into the exit status.
    struct Stopped
    {
      int signal;
    };
  } // namespace StopSignals
} // namespace ViscoContact

#endif
