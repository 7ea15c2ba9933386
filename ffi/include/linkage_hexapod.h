/*
 * linkage_hexapod.h — C interface to linkage's 6-6 hexapod kinematics (crate linkage-ffi,
 * static library liblinkage_ffi.a). Written by hand; ffi/src/exports.rs is the other side.
 *
 * A handle lives in storage the caller owns (no allocation, no destructor). Inverse
 * kinematics is closed form. Forward kinematics tracks one branch (assembly mode): the first
 * call starts at the pose it is given, later calls continue from the last accepted solution
 * and refuse any result on another branch. Every function returns a status code: 0 is a
 * solution on the tracked branch, > 0 a solver refusal, < 0 a call that was not attempted.
 * Outputs are written only on 0. A handle is not thread-safe: one caller at a time.
 */
#ifndef LINKAGE_HEXAPOD_H
#define LINKAGE_HEXAPOD_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Status codes. */
#define LINKAGE_OK 0                  /* converged on the tracked branch */
#define LINKAGE_FOLD 1                /* the legs leave the workspace through a fold (direct singularity) */
#define LINKAGE_BRANCH_CHANGED 2      /* the only solution found is on another branch: refused */
#define LINKAGE_NOT_CONVERGED 3       /* Newton did not converge within the iteration limit */
#define LINKAGE_STEP_TOO_SMALL 4      /* continuation's step size underflowed */
#define LINKAGE_SINGULAR 5            /* B became singular and the method could not go on */
#define LINKAGE_TOLERANCE_NOT_MET 6   /* stopped short of the requested tolerance */
#define LINKAGE_FAILED 7              /* another non-ok solver outcome (never a success) */
#define LINKAGE_UNVERIFIED 8          /* converged, but by a method that cannot establish the branch */
#define LINKAGE_UNPROVEN 9            /* certification on: the step was not proven to keep the branch */
#define LINKAGE_NULL_POINTER (-1)
#define LINKAGE_NON_FINITE (-2)       /* a NaN or infinite leg, pose or option value */
#define LINKAGE_INVALID_INPUT (-3)    /* a leg length out of range (not positive), or an angle word beyond 2^16 rad (3.75e6 deg) */
#define LINKAGE_INVALID_GEOMETRY (-4) /* non-finite geometry or a collinear platform frame */
#define LINKAGE_INVALID_OPTIONS (-5)  /* tolerance not finite and positive, or zero iterations */
#define LINKAGE_POSE_MISMATCH (-6)    /* the start pose does not match the legs */
#define LINKAGE_SINGULAR_START (-7)   /* the start configuration is singular */
#define LINKAGE_INCONSISTENT_START (-8)
#define LINKAGE_UNREACHABLE (-9)      /* no leg lengths reach that pose */
#define LINKAGE_BAD_STORAGE (-10)

/* Bytes and alignment of caller storage for one handle (checked at compile time in Rust;
   linkage_hexapod_size() gives the exact size). */
#define LINKAGE_HEXAPOD_STORAGE 8192

typedef struct linkage_hexapod {
    _Alignas(16) unsigned char opaque[LINKAGE_HEXAPOD_STORAGE];
} linkage_hexapod;

/* Joint centres: base[i] in the base (world) frame, platform[i] in the platform frame;
   leg i joins base[i] to platform[i]. */
typedef struct linkage_geometry {
    double base[6][3];
    double platform[6][3];
} linkage_geometry;

/* LinuxCNC's pose words: X Y Z, then A B C in degrees, R = Rz(C) Ry(B) Rx(A),
   p_world = R p_platform + (X, Y, Z). */
typedef struct linkage_pose {
    double x, y, z, a, b, c;
} linkage_pose;

typedef struct linkage_report {
    double proximity;           /* |det B| / |det B at the start|: 0 at a direct singularity */
    int32_t status;             /* the call's status code */
    uint32_t newton_iterations; /* Newton iterations spent */
    int32_t fell_back;          /* 1: the fast path failed and continuation took over */
    int32_t started;            /* 1: this call started tracking */
    int32_t certified;          /* 1: certification on and the step proven (interval certificate) */
} linkage_report;

size_t linkage_hexapod_size(void);

/* Builds a handle in h for the geometry; h holds no handle on a non-zero return. */
int32_t linkage_hexapod_init(linkage_hexapod *h, const linkage_geometry *geometry);

/* Replaces the geometry (tracking restarts at the next forward call); unchanged on error. */
int32_t linkage_hexapod_set_geometry(linkage_hexapod *h, const linkage_geometry *geometry);

/* Convergence tolerance (geometry length units) and Newton iteration limit; a change
   restarts tracking at the next forward call. */
int32_t linkage_hexapod_set_options(linkage_hexapod *h, double tolerance, uint32_t max_iterations);

/* genhexkins' strut length correction for screw-driven struts: base_n[i] and platform_n[i]
   are the axes of strut i's end joints (base frame, platform frame), screw_lead the length
   per turn; a strut's joint value is its length plus screw_lead * asin(n3 . n2) / 2 pi, with
   n3 = u x (base_n x u) and n2 = (R platform_n) x u, both made unit, u the strut's direction.
   A zero screw_lead turns it off (the default). A change restarts tracking. */
typedef struct linkage_strut_correction {
    double base_n[6][3];
    double platform_n[6][3];
    double screw_lead;
} linkage_strut_correction;

int32_t linkage_hexapod_set_strut_correction(linkage_hexapod *h,
                                             const linkage_strut_correction *correction);

/* The corrections linkage_hexapod_inverse adds to the struts at pose (zeros when off);
   out is written only on 0. */
int32_t linkage_hexapod_strut_corrections(const linkage_hexapod *h, const linkage_pose *pose,
                                          double out[6]);

/* Certification of every forward step (0 off, the default; 1 on): each accepted sample's
   step from the last one is proven by interval arithmetic to stay on the tracked branch
   (report.certified), and a step that cannot be proven is refused with LINKAGE_UNPROVEN.
   A change restarts tracking. */
int32_t linkage_hexapod_set_certify(linkage_hexapod *h, int32_t on);

/* Forgets the tracked branch. */
int32_t linkage_hexapod_reset(linkage_hexapod *h);

/* 1 while tracking, 0 if not, LINKAGE_NULL_POINTER for null. */
int32_t linkage_hexapod_is_tracking(const linkage_hexapod *h);

/* Leg lengths for a pose. */
int32_t linkage_hexapod_inverse(const linkage_hexapod *h, const linkage_pose *pose, double legs[6]);

/* Forward kinematics. pose is in-out: when not tracking, the pose to start at (the legs must
   match it to 1 % of the platform's size); when tracking, the angle words nearest which to
   report (each within 2^16 rad, about 3.75e6 degrees). Written only on LINKAGE_OK, and then its
   strut lengths match the legs to the tolerance. report may be NULL. */
int32_t linkage_hexapod_forward(linkage_hexapod *h, const double legs[6], linkage_pose *pose,
                                linkage_report *report);

/* A static lowercase name for a status code ("ok", "branch_changed", ...); never NULL. */
const char *linkage_status_name(int32_t code);

#ifdef __cplusplus
}
#endif

#endif /* LINKAGE_HEXAPOD_H */
