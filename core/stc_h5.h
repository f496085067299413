/* Scalar and short vector HDF5 attributes, shared by the file readers and writers of every
 * layer (surface maps, friction tables).  Private (not installed).
 * put_*: 0 on success, -1 on failure; get_*: 0 when the attribute exists,
 * holds exactly one element of a readable type, and was read; -1 otherwise
 * (a foreign file's array attribute is never read into a single value);
 * get_dv: 0 when the attribute is a one-dimensional array of at most cap
 * numbers, read into v[0..*n-1].
 * Call inside H5E_BEGIN_TRY where HDF5's own error printing is unwanted. */
#ifndef STICTION_STC_H5_H
#define STICTION_STC_H5_H

#include <stddef.h>

#include <hdf5.h>

int stc_h5_attr_exists(hid_t obj, const char *name);
int stc_h5_put_d(hid_t obj, const char *name, double v);
int stc_h5_put_i(hid_t obj, const char *name, int v);
int stc_h5_put_u(hid_t obj, const char *name, unsigned long v);
int stc_h5_put_s(hid_t obj, const char *name, const char *v); /* fixed-length, NUL-terminated */
int stc_h5_get_d(hid_t obj, const char *name, double *v);
int stc_h5_get_i(hid_t obj, const char *name, int *v);
int stc_h5_get_u(hid_t obj, const char *name, unsigned long *v);
int stc_h5_get_s(hid_t obj, const char *name, char *buf, size_t cap); /* fixed-length < cap */
int stc_h5_put_dv(hid_t obj, const char *name, int n, const double *v); /* n >= 1 */
int stc_h5_get_dv(hid_t obj, const char *name, int cap, double *v, int *n);

#endif
