/* path_internal — what path.c (the curves) and path_file.c (the file) share. Pure C. */
#ifndef FATHOM_PATH_INTERNAL_H
#define FATHOM_PATH_INTERNAL_H

#include "view/path.h"

/* Orientation as yaw, then pitch, then roll (camera.h) and back; a frame's angles from its unit forward
 * f and right r. */
void path_q_from_angles(double yaw, double pitch, double roll, double q[4]);
void path_q_to_angles(const double q[4], double *yaw, double *pitch, double *roll);
void path_frame_angles(const double f[3], const double r[3], double *yaw, double *pitch, double *roll);
double path_q_dot(const double a[4], const double b[4]);
double path_dist(const double a[3], const double b[3]);
/* After the keys are read: the arc-length tables and the speeds at the keys. */
void path_prepare(path *p);

#endif
