/* The PETSc and SLEPc headers slideline binds; build.rs restricts the generated FFI to the calls listed there. */
#include <petscsys.h>
#include <petscvec.h>
#include <petscmat.h>
#include <petscis.h>
#include <petscksp.h>
#include <petscsnes.h>
#include <petsclog.h>
#include <slepceps.h>
