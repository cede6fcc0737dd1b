#ifndef viscoplastic_contact_blas_threads_h
#define viscoplastic_contact_blas_threads_h

namespace ViscoContact
{
  // @sect3{Threads of the BLAS}
  //
  // The program uses the system's BLAS (libblas.so.3, which Debian's
  // alternatives point to one of several builds). The threaded OpenBLAS
  // that scripts/install_dependencies.sh installs would by default run
  // every BLAS call on all cores of the machine, on top of the MPI ranks
  // and the stress update's threads. So the program keeps the BLAS on one
  // thread (main() calls set_blas_threads(1) at start-up) and gives it the
  // rank's threads only where dense kernels do most of the work: the
  // supernodal factorisation and the solves with many right-hand sides
  // (direct_solver.cc). With another BLAS, which has no threads to set,
  // both do nothing.

  // Sets the number of BLAS threads; returns the number before (1 if the
  // BLAS has no such setting).
  unsigned int
  set_blas_threads(const unsigned int n_threads);

  // The number of BLAS threads now (1 if the BLAS has no such setting).
  unsigned int
  blas_threads();

  // The BLAS threads for one scope: the rank's threads
  // (MultithreadInfo::n_threads()) from construction, the number before
  // from destruction (also when an exception leaves the scope). For the
  // same scope CHOLMOD's own OpenMP loops (which scatter the updates
  // between supernodes) run on the calling thread only: a second pool of
  // threads would compete with the BLAS's for the cores.
  // (At 526k dofs, by hand, five paired runs: the set-up of the 2D static
  // scene took 2.36 s against 2.58 s in the median, with less spread.)
  class BlasThreadsOfRank
  {
  public:
    BlasThreadsOfRank();
    ~BlasThreadsOfRank();
    BlasThreadsOfRank(const BlasThreadsOfRank &) = delete;
    BlasThreadsOfRank &
    operator=(const BlasThreadsOfRank &)
      = delete;

  private:
    unsigned int previous;
    int          previous_openmp;
  };
} // namespace ViscoContact

#endif
