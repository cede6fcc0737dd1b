#ifndef viscoplastic_contact_stop_signals_h
#define viscoplastic_contact_stop_signals_h

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
  // The handler only records the signal; the time loop asks once per step,
  // and the ranks agree on the answer with a maximum over the ranks, so that
  // all stop after the same step even if only one rank got the signal.
  namespace StopSignals
  {
    // Installs the handler for SIGTERM, SIGINT and SIGUSR1.
    void
    install();

    // The number of the first signal received, 0 if none.
    int
    received();

    // SIGTERM, SIGINT, SIGUSR1 (or "signal N").
    std::string
    name(const int signal);

    // Thrown by the time loop on every rank after the checkpoint of the
    // step at which it stopped; main() turns it into the exit status.
    struct Stopped
    {
      int signal;
    };
  } // namespace StopSignals
} // namespace ViscoContact

#endif
