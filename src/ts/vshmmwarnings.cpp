/*
  The one channel of the warnings a user must see without asking: the stability and separation
  checks, the accuracy control's step accepted above the tolerance, and the split that produced
  Inf or NaN. They go to the TS's warnings viewer (TSVSHMMSetWarningsViewer(),
  -ts_vshmm_warnings_viewer): PETSC_STDERR by default, an ASCII viewer (a file), or nowhere.
  Notes go through PetscInfo(), results through the statistics and -ts_view.
*/
#include "vshmmimpl.hpp"

#include <cstdarg>
#include <vector>

/* Formats as PetscFPrintf() does (PETSc's %g) and prints on the first rank: to the warnings
   viewer if one is set, else to PETSC_STDERR as it is at the time (a program may redirect it;
   the communicator's cached stderr viewer would keep the stream it was made with); nothing with
   TSVSHMMSetWarningsViewer(ts, NULL). Not collective. */
PetscErrorCode TSVSHMMWarn_Private(TS ts, const char format[], ...)
{
  TS_VSHMM         *vs = (TS_VSHMM *)ts->data;
  std::vector<char> text(1024);
  size_t            length;
  va_list           args;

  PetscFunctionBegin;
  if (vs->warnings_none) PetscFunctionReturn(0);
  va_start(args, format);
  PetscErrorCode ierr = PetscVSNPrintf(text.data(), text.size(), format, &length, args);
  va_end(args);
  PetscCall(ierr);
  if (length >= text.size()) { /* longer than the first guess: once more with the length it needs */
    text.resize(length + 1);
    va_start(args, format);
    ierr = PetscVSNPrintf(text.data(), text.size(), format, &length, args);
    va_end(args);
    PetscCall(ierr);
  }
  if (vs->warnings) PetscCall(PetscViewerASCIIPrintf(vs->warnings, "%s", text.data()));
  else PetscCall(PetscFPrintf(PetscObjectComm((PetscObject)ts), PETSC_STDERR, "%s", text.data()));
  PetscFunctionReturn(0);
}
