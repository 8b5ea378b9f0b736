/*
  PETSc's option readers as the TS type (TSSetFromOptions_VSHMM) and the spectral component
  (VSHMMSpectralSetFromOptions) use them, for any PetscObject: one implementation, included by
  both libraries (private; not installed).

  Each reader is PETSc's own (PetscOptionsReal, ...Int, ...Bool, ...Enum, ...String,
  ...RealArray, ...IntArray, ...StringArray, so -help shows the type and the current value),
  called inside the object's options block, plus the checks of what PETSc accepts but the library
  refuses, made after reading:
  - an option given without a value (PETSc's numeric and list readers take it for an option not
    given, its enum reader for the first name);
  - an empty list item ("1,,2", "1,2,": PETSc's list readers drop it);
  - an integer beyond PetscInt (PETSc 3.18 wraps it around: 99999999999999999999 reads as -1).
  A value the reader cannot read becomes an error naming the option, the value and what the
  option takes. Lists take as many values as the user gives: the buffer is sized from the
  option's value (its number of commas). PETSc's integer ranges a-b are read as far as the list
  has items; a wider range is refused with PETSc's message.
*/
#pragma once

#include <petsc/private/petscimpl.h>

#include <cstring>
#include <string>
#include <vector>

/* The option as the user types it: -<prefix><name>, from opt = "-<name>". */
static inline std::string VSHMMOptionName(PetscObject obj, const char opt[])
{
  return std::string("-") + (obj->prefix ? obj->prefix : "") + (opt + 1);
}

/* The option's value in the object's options database (found = PETSC_FALSE: not given; value
   NULL: given without a value). */
static inline PetscErrorCode VSHMMOptionFind(PetscObject obj, const char opt[], const char **value, PetscBool *found)
{
  PetscFunctionBegin;
  PetscCall(PetscOptionsFindPair(obj->options, obj->prefix, opt, value, found));
  PetscFunctionReturn(0);
}

/* The checks made before reading (see the head of this file). takes says what the option takes,
   for the messages. */
static inline PetscErrorCode VSHMMOptionCheckValue(PetscObject obj, const char opt[], const char takes[], bool list, bool integer)
{
  MPI_Comm    comm = PetscObjectComm(obj);
  const char *value;
  PetscBool   found;

  PetscFunctionBegin;
  PetscCall(VSHMMOptionFind(obj, opt, &value, &found));
  if (!found) PetscFunctionReturn(0);
  PetscCheck(value && value[0], comm, PETSC_ERR_ARG_WRONG, "%s is given without a value: it takes %s", VSHMMOptionName(obj, opt).c_str(), takes);
  if (list) {
    const size_t n = std::strlen(value);
    PetscCheck(value[0] != ',' && value[n - 1] != ',' && !std::strstr(value, ",,"), comm, PETSC_ERR_ARG_WRONG, "%s %s has an empty item (two commas in a row, or a comma at an end): it takes %s", VSHMMOptionName(obj, opt).c_str(), value, takes);
  }
  if (integer) { /* every run of digits must fit a PetscInt */
    for (const char *p = value; *p;) {
      if (*p < '0' || *p > '9') {
        ++p;
        continue;
      }
      const char *start = p;
      double      v     = 0;
      for (; *p >= '0' && *p <= '9'; ++p) v = 10 * v + (*p - '0');
      PetscCheck(v <= (double)PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %s: %.*s is beyond the largest integer %" PetscInt_FMT ": it takes %s", VSHMMOptionName(obj, opt).c_str(), value, (int)(p - start), start, (PetscInt)PETSC_MAX_INT, takes);
    }
  }
  PetscFunctionReturn(0);
}

/* Runs read (one of PETSc's readers); a value it cannot read becomes an error naming the option,
   its value, PETSc's reason and what the option takes. */
template <typename Read>
static inline PetscErrorCode VSHMMOptionRead(PetscObject obj, const char opt[], const char takes[], Read read)
{
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  ierr = read();
  PetscCall(PetscPopErrorHandler());
  if (ierr) {
    const char *text, *value;
    char       *specific = nullptr;
    PetscBool   found;

    PetscCall(VSHMMOptionFind(obj, opt, &value, &found));
    PetscErrorMessage(ierr, &text, &specific);
    const std::string reason = specific && specific[0] ? specific : (text ? text : "unreadable");
    SETERRQ(PetscObjectComm(obj), ierr, "%s %s: %s; the option takes %s", VSHMMOptionName(obj, opt).c_str(), value ? value : "", reason.c_str(), takes);
  }
  PetscFunctionReturn(0);
}

/* The number of items of a list option's value (0 if it is absent or empty). */
static inline PetscErrorCode VSHMMOptionItems(PetscObject obj, const char opt[], PetscInt *n)
{
  const char *value;
  PetscBool   found;

  PetscFunctionBegin;
  *n = 0;
  PetscCall(VSHMMOptionFind(obj, opt, &value, &found));
  if (found && value && value[0]) {
    *n = 1;
    for (const char *p = value; *p; ++p) *n += *p == ',';
  }
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Scalars: PETSc's reader after the checks; value holds the current value on entry (-help shows it). */

static inline PetscErrorCode VSHMMOptionsReal(PetscOptionItems *PetscOptionsObject, PetscObject obj, const char opt[], const char text[], const char man[], PetscReal *value, PetscBool *set)
{
  const char *takes = "a real number";

  PetscFunctionBegin;
  PetscCall(VSHMMOptionCheckValue(obj, opt, takes, false, false));
  PetscCall(VSHMMOptionRead(obj, opt, takes, [&]() { return PetscOptionsReal(opt, text, man, *value, value, set); }));
  PetscFunctionReturn(0);
}

static inline PetscErrorCode VSHMMOptionsInt(PetscOptionItems *PetscOptionsObject, PetscObject obj, const char opt[], const char text[], const char man[], PetscInt *value, PetscBool *set)
{
  const char *takes = "an integer";

  PetscFunctionBegin;
  PetscCall(VSHMMOptionCheckValue(obj, opt, takes, false, true));
  PetscCall(VSHMMOptionRead(obj, opt, takes, [&]() { return PetscOptionsInt(opt, text, man, *value, value, set); }));
  PetscFunctionReturn(0);
}

/* A flag alone means true, as everywhere in PETSc. */
static inline PetscErrorCode VSHMMOptionsBool(PetscOptionItems *PetscOptionsObject, PetscObject obj, const char opt[], const char text[], const char man[], PetscBool *value, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(VSHMMOptionRead(obj, opt, "true or false", [&]() { return PetscOptionsBool(opt, text, man, *value, value, set); }));
  PetscFunctionReturn(0);
}

/* An unknown name is PETSc's error, which names the option and the names it takes. */
template <typename E>
static inline PetscErrorCode VSHMMOptionsEnum(PetscOptionItems *PetscOptionsObject, PetscObject obj, const char opt[], const char text[], const char man[], const char *const names[], E *value, PetscBool *set)
{
  PetscEnum   e = (PetscEnum)*value;
  std::string takes;

  PetscFunctionBegin;
  for (PetscInt i = 0; names[i] && names[i + 1] && names[i + 2]; ++i) takes += (i ? ", " : "one of ") + std::string(names[i]); /* the list ends with the enum's name, its prefix and NULL */
  PetscCall(VSHMMOptionCheckValue(obj, opt, takes.c_str(), false, false));
  PetscCall(PetscOptionsEnum(opt, text, man, names, e, &e, set));
  *value = (E)e;
  PetscFunctionReturn(0);
}

/* A string of any length (value: the current one on entry). */
static inline PetscErrorCode VSHMMOptionsString(PetscOptionItems *PetscOptionsObject, PetscObject obj, const char opt[], const char text[], const char man[], const char takes[], std::string &value, PetscBool *set)
{
  const char *given;
  PetscBool   found;

  PetscFunctionBegin;
  PetscCall(VSHMMOptionCheckValue(obj, opt, takes, false, false));
  PetscCall(VSHMMOptionFind(obj, opt, &given, &found));
  std::vector<char> buf(PetscMax(value.size(), found && given ? std::strlen(given) : 0) + 1);
  PetscCall(PetscStrncpy(buf.data(), value.c_str(), buf.size()));
  PetscCall(PetscOptionsString(opt, text, man, buf.data(), buf.data(), buf.size(), set));
  if (*set) value = buf.data();
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Lists of any length: v holds the current values on entry (-help shows them) and the values
   given on return (unchanged if the option is absent). */

template <typename T, typename Read>
static inline PetscErrorCode VSHMMOptionsList_Private(PetscObject obj, const char opt[], const char takes[], bool integer, std::vector<T> &v, PetscBool *set, Read read)
{
  PetscInt       n;
  std::vector<T> buf(v);

  PetscFunctionBegin;
  PetscCall(VSHMMOptionCheckValue(obj, opt, takes, true, integer));
  PetscCall(VSHMMOptionItems(obj, opt, &n));
  buf.resize(PetscMax(1, PetscMax(n, (PetscInt)v.size())));
  n = (PetscInt)buf.size();
  PetscCall(VSHMMOptionRead(obj, opt, takes, [&]() { return read(buf.data(), &n); }));
  if (*set) v.assign(buf.begin(), buf.begin() + n);
  PetscFunctionReturn(0);
}

static inline PetscErrorCode VSHMMOptionsRealList(PetscOptionItems *PetscOptionsObject, PetscObject obj, const char opt[], const char text[], const char man[], std::vector<PetscReal> &v, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(VSHMMOptionsList_Private(obj, opt, "a comma-separated list of real numbers", false, v, set, [&](PetscReal *a, PetscInt *n) { return PetscOptionsRealArray(opt, text, man, a, n, set); }));
  PetscFunctionReturn(0);
}

static inline PetscErrorCode VSHMMOptionsIntList(PetscOptionItems *PetscOptionsObject, PetscObject obj, const char opt[], const char text[], const char man[], std::vector<PetscInt> &v, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(VSHMMOptionsList_Private(obj, opt, "a comma-separated list of integers", true, v, set, [&](PetscInt *a, PetscInt *n) { return PetscOptionsIntArray(opt, text, man, a, n, set); }));
  PetscFunctionReturn(0);
}

/* A list of names (-help shows no current value for string lists: PETSc's reader has none). */
static inline PetscErrorCode VSHMMOptionsStringList(PetscOptionItems *PetscOptionsObject, PetscObject obj, const char opt[], const char text[], const char man[], std::vector<std::string> &v, PetscBool *set)
{
  const char         *takes = "a comma-separated list of names";
  PetscInt            n;
  std::vector<char *> buf;

  PetscFunctionBegin;
  PetscCall(VSHMMOptionCheckValue(obj, opt, takes, true, false));
  PetscCall(VSHMMOptionItems(obj, opt, &n));
  buf.assign(PetscMax(1, n), nullptr);
  n = (PetscInt)buf.size();
  PetscCall(PetscOptionsStringArray(opt, text, man, buf.data(), &n, set));
  if (*set) v.assign(buf.begin(), buf.begin() + n);
  for (PetscInt i = 0; *set && i < n; ++i) PetscCall(PetscFree(buf[i]));
  PetscFunctionReturn(0);
}
