// The thread count of a threaded OpenBLAS, found at run time: the BLAS is
// whichever build libblas.so.3 points to, and only OpenBLAS has these
// functions, so they are looked up by name instead of linked against. The
// same for the OpenMP runtime, which only CHOLMOD brings in.

#include <deal.II/base/multithread_info.h>

#include "back_ends/blas_threads.h"

#include <dlfcn.h>

#include <algorithm>

namespace ViscoContact
{
  namespace
  {
    using SetThreads = void (*)(int);
    using GetThreads = int (*)();

    // A function of the libraries loaded, by name, or null where none has
    // it: OpenBLAS's openblas_set/get_num_threads (no other BLAS has them)
    // and OpenMP's omp_set_num_threads and omp_get_max_threads (for the
    // calling thread; only CHOLMOD brings in an OpenMP runtime).
    template <typename Function>
    Function
    function_named(const char *name)
    {
      return reinterpret_cast<Function>(dlsym(RTLD_DEFAULT, name));
    }
  } // namespace



  unsigned int
  set_blas_threads(const unsigned int n_threads)
  {
    const auto set = function_named<SetThreads>("openblas_set_num_threads");
    if (set == nullptr)
      return 1;
    const unsigned int previous = blas_threads();
    set(static_cast<int>(std::max(n_threads, 1u)));
    return previous;
  }



  unsigned int
  blas_threads()
  {
    const auto get = function_named<GetThreads>("openblas_get_num_threads");
    return get != nullptr ? std::max(get(), 1) : 1;
  }



  BlasThreadsOfRank::BlasThreadsOfRank()
    : previous(set_blas_threads(dealii::MultithreadInfo::n_threads()))
    , previous_openmp(0)
  {
    const auto set = function_named<SetThreads>("omp_set_num_threads");
    const auto get = function_named<GetThreads>("omp_get_max_threads");
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
      function_named<SetThreads>("omp_set_num_threads")(previous_openmp);
  }

} // namespace ViscoContact
