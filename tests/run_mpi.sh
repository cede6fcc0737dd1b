#!/bin/bash
# Runs a command on N MPI ranks (directly for N = 1, as a singleton that
# starts no Open MPI daemon: a fifth of a second less per run). Open MPI
# refuses to run as root unless told that this is intended; test machines
# often are.
#   run_mpi.sh N COMMAND...
n=$1
shift
if [ "$n" -eq 1 ]; then
  export OMPI_MCA_ess_singleton_isolated=1
  exec "$@"
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exec mpirun -np "$n" --oversubscribe "$@"
