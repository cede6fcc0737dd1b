// The thread count of a threaded OpenBLAS, found at run time: the BLAS is
// whichever build libblas.so.3 points to, and only OpenBLAS has these
// functions, so they are looked up by name instead of linked against. The
// same for the OpenMP runtime, which only CHOLMOD brings in.

#include <deal.II/base/multithread_info.h>

#include "blas_threads.h"

#include <dlfcn.h>

#include <algorithm>

namespace ViscoContact
{
  namespace
  {
    using SetThreads = void (*)(int);
    using GetThreads = int (*)();

    // OpenBLAS's two functions, or null with another BLAS.
    SetThreads
    openblas_set_num_threads()
    {
      return reinterpret_cast<SetThreads>(
        dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    }

    GetThreads
    openblas_get_num_threads()
    {
      return reinterpret_cast<GetThreads>(
        dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    }

    // OpenMP's two functions for the calling thread, or null without an
    // OpenMP runtime.
    SetThreads
    omp_set_num_threads()
    {
      return reinterpret_cast<SetThreads>(
        dlsym(RTLD_DEFAULT, "omp_set_num_threads"));
    }

    GetThreads
    omp_get_max_threads()
    {
      return reinterpret_cast<GetThreads>(
        dlsym(RTLD_DEFAULT, "omp_get_max_threads"));
    }
  } // namespace



  unsigned int
  set_blas_threads(const unsigned int n_threads)
  {
    const SetThreads set = openblas_set_num_threads();
    if (set == nullptr)
      return 1;
    const unsigned int previous = blas_threads();
    set(static_cast<int>(std::max(n_threads, 1u)));
    return previous;
  }



  unsigned int
  blas_threads()
  {
    const GetThreads get = openblas_get_num_threads();
    return get != nullptr ? std::max(get(), 1) : 1;
  }



  BlasThreadsOfRank::BlasThreadsOfRank()
    : previous(set_blas_threads(dealii::MultithreadInfo::n_threads()))
    , previous_openmp(0)
  {
    const SetThreads set = omp_set_num_threads();
    const GetThreads get = omp_get_max_threads();
    if (set != nullptr && get != nullptr)
      {
        previous_openmp = get();
        set(1);
      }
  }



  BlasThreadsOfRank::~BlasThreadsOfRank()
  {
    set_blas_threads(previous);
    if (previous_openmp > 0)
      omp_set_num_threads()(previous_openmp);
  }

} // namespace ViscoContact
