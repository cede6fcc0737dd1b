#!/bin/bash
# Runs a command on N MPI ranks (directly for N = 1). Open MPI refuses to
# run as root unless told that this is intended; test machines often are.
#   run_mpi.sh N COMMAND...
n=$1
shift
if [ "$n" -eq 1 ]; then
  exec "$@"
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exec mpirun -np "$n" --oversubscribe "$@"
