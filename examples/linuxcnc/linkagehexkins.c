/*
 * linkagehexkins — LinuxCNC kinematics for 6-6 hexapods (Stewart platforms), a drop-in for
 * genhexkins built on linkage (crate linkage-ffi, ffi/include/linkage_hexapod.h).
 *
 * Inverse kinematics: strut lengths |t + R a_i - b_i|, as genhexkins.
 * Forward kinematics: linkage's trajectory tracker. The first call after loading, a
 * geometry change or a reset starts at the pose LinuxCNC passes in (after homing that is
 * [TRAJ]HOME, which must match the home strut lengths, as genhexkins also needs); every
 * later call continues from the last accepted solution and never returns a pose on another
 * assembly mode. A refusal (the legs cannot be reached on the tracked branch) returns -1
 * and sets fwd-kins-fail, like genhexkins' non-convergence; LinuxCNC then marks its
 * Cartesian feedback invalid and the tracker keeps its last good state.
 *
 * Pins (PREFIX is the module parameter `prefix`, default "linkagehexkins"; load with
 * prefix=genhexkins to keep a genhexkins HAL file as it is):
 *   PREFIX.base.N.{x,y,z}, PREFIX.platform.N.{x,y,z}   joint centres, as genhexkins
 *   PREFIX.spindle-offset, PREFIX.tool-offset         added to every joint's z, as genhexkins
 *   PREFIX.convergence-criterion                      the tracker's tolerance (length units)
 *   PREFIX.limit-iterations                           the tracker's Newton iteration limit
 *   PREFIX.max-error                                  accepted for compatibility, not used
 *   PREFIX.base-n.N.*, PREFIX.platform-n.N.*, PREFIX.screw-lead   the strut length correction
 *       for screw-driven struts, as genhexkins (off while screw-lead is 0, the default);
 *       forward kinematics solves for it (a fixed point around the tracker)
 *   PREFIX.correction.N (out)        each strut's correction at the last inverse call
 *   PREFIX.fwd-kins-fail (out)       the last forward call failed or was refused
 *   PREFIX.last-iterations (out), PREFIX.max-iterations (out)   Newton iterations
 * and, beyond genhexkins:
 *   PREFIX.status (s32 out)          the last forward call's linkage status code (0 ok,
 *                                    2 branch_changed, 1 fold, ... see linkage_hexapod.h)
 *   PREFIX.refused (bit out)         the last forward call was a solver refusal (status > 0)
 *   PREFIX.refusals (u32 out)        how many forward calls were refused so far
 *   PREFIX.failures (u32 out)        how many forward calls failed so far, for any reason
 *                                    (fwd-kins-fail only says whether the last one did)
 *   PREFIX.last-failure (s32 out)    the status code of the latest failed call
 *   PREFIX.tracking (bit out)        a branch is being tracked
 *   PREFIX.proximity (float out)     |det B| / |det B at the start| (0 at a singularity)
 *   PREFIX.min-proximity (float out) its smallest value since tracking started
 *   PREFIX.fell-back (bit out)       the last call needed continuation (a hard step)
 *   PREFIX.reset (bit in)            while true, every forward call starts afresh
 *   PREFIX.certify (bit in)          prove every forward step by interval certificates (an
 *                                    unproven step is refused, status 9 unproven)
 *   PREFIX.certified (bit out)       the last forward call's step was proven
 */

#include "rtapi.h"
#include "rtapi_app.h"
#include "rtapi_math.h"
#include "rtapi_string.h"
#include "hal.h"
#include "kinematics.h"
#include "genhexkins.h" /* the default geometry, so that defaults match too */
#include "linkage_hexapod.h"

MODULE_LICENSE("Dual MIT/GPL");
MODULE_DESCRIPTION("6-6 hexapod kinematics by linkage: branch-tracking forward kinematics");

static char *prefix = "linkagehexkins";
RTAPI_MP_STRING(prefix, "prefix of the HAL pin names (genhexkins to keep a genhexkins HAL file)");

#define STRUTS 6

static struct haldata {
    hal_float_t *base[STRUTS][3];
    hal_float_t *platform[STRUTS][3];
    hal_float_t *base_n[STRUTS][3];
    hal_float_t *platform_n[STRUTS][3];
    hal_float_t *correction[STRUTS];
    hal_float_t *screw_lead, *spindle_offset, *tool_offset;
    hal_float_t *conv_criterion, *max_error;
    hal_u32_t *iter_limit, *last_iter, *max_iter;
    hal_bit_t *fwd_kins_fail;
    hal_s32_t *status, *last_failure;
    hal_bit_t *refused, *tracking, *fell_back, *reset, *certify, *certified;
    hal_u32_t *refusals, *failures;
    hal_float_t *proximity, *min_proximity;
} *haldata;

static int comp_id;
/* The handle: static storage, built once at load, never freed (it owns nothing). */
static linkage_hexapod hex;
static linkage_geometry current;
static linkage_strut_correction current_correction;

/* Reads the geometry and options pins; hands a changed geometry or option to the handle. */
static int sync_pins(void)
{
    linkage_geometry g;
    linkage_strut_correction c;
    double dz = *haldata->spindle_offset + *haldata->tool_offset;
    int i, k, rc;

    for (i = 0; i < STRUTS; i++) {
        for (k = 0; k < 3; k++) {
            g.base[i][k] = *haldata->base[i][k];
            g.platform[i][k] = *haldata->platform[i][k];
        }
        g.base[i][2] += dz;
        g.platform[i][2] += dz;
    }
    if (memcmp(&g, &current, sizeof g) != 0) {
        rc = linkage_hexapod_set_geometry(&hex, &g);
        if (rc != LINKAGE_OK) {
            return rc;
        }
        current = g;
    }
    for (i = 0; i < STRUTS; i++) {
        for (k = 0; k < 3; k++) {
            c.base_n[i][k] = *haldata->base_n[i][k];
            c.platform_n[i][k] = *haldata->platform_n[i][k];
        }
    }
    c.screw_lead = *haldata->screw_lead;
    if (memcmp(&c, &current_correction, sizeof c) != 0) {
        rc = linkage_hexapod_set_strut_correction(&hex, &c);
        if (rc != LINKAGE_OK) {
            return rc;
        }
        current_correction = c;
    }
    rc = linkage_hexapod_set_certify(&hex, *haldata->certify ? 1 : 0);
    if (rc != LINKAGE_OK) {
        return rc;
    }
    rc = linkage_hexapod_set_options(&hex, *haldata->conv_criterion, *haldata->iter_limit);
    if (rc != LINKAGE_OK) {
        return rc;
    }
    if (*haldata->reset) {
        linkage_hexapod_reset(&hex);
    }
    return LINKAGE_OK;
}

int kinematicsForward(const double *joints, EmcPose *pos,
                      const KINEMATICS_FORWARD_FLAGS *fflags,
                      KINEMATICS_INVERSE_FLAGS *iflags)
{
    linkage_pose p;
    linkage_report report = {0};
    int rc;
    (void)fflags;
    (void)iflags;

    rc = sync_pins();
    if (rc == LINKAGE_OK) {
        p.x = pos->tran.x; p.y = pos->tran.y; p.z = pos->tran.z;
        p.a = pos->a; p.b = pos->b; p.c = pos->c;
        rc = linkage_hexapod_forward(&hex, joints, &p, &report);
    }
    *haldata->status = rc;
    *haldata->tracking = linkage_hexapod_is_tracking(&hex) == 1;
    *haldata->last_iter = report.newton_iterations;
    if (rc != LINKAGE_OK) {
        *haldata->fwd_kins_fail = 1;
        *haldata->certified = 0;
        *haldata->failures += 1;
        *haldata->last_failure = rc;
        *haldata->refused = rc > 0;
        if (rc > 0) {
            *haldata->refusals += 1;
        }
        return -1;
    }
    if (report.started) {
        *haldata->min_proximity = report.proximity;
    }
    if (report.newton_iterations > *haldata->max_iter) {
        *haldata->max_iter = report.newton_iterations;
    }
    *haldata->proximity = report.proximity;
    if (report.proximity < *haldata->min_proximity) {
        *haldata->min_proximity = report.proximity;
    }
    *haldata->fell_back = report.fell_back != 0;
    *haldata->certified = report.certified != 0;
    *haldata->fwd_kins_fail = 0;
    *haldata->refused = 0;
    pos->tran.x = p.x; pos->tran.y = p.y; pos->tran.z = p.z;
    pos->a = p.a; pos->b = p.b; pos->c = p.c;
    pos->u = pos->v = pos->w = 0.0;
    return 0;
}

int kinematicsInverse(const EmcPose *pos, double *joints,
                      const KINEMATICS_INVERSE_FLAGS *iflags,
                      KINEMATICS_FORWARD_FLAGS *fflags)
{
    linkage_pose p;
    double legs[STRUTS], corrections[STRUTS];
    int i;
    (void)iflags;
    (void)fflags;

    if (sync_pins() != LINKAGE_OK) {
        return -1;
    }
    p.x = pos->tran.x; p.y = pos->tran.y; p.z = pos->tran.z;
    p.a = pos->a; p.b = pos->b; p.c = pos->c;
    if (linkage_hexapod_inverse(&hex, &p, legs) != LINKAGE_OK
        || linkage_hexapod_strut_corrections(&hex, &p, corrections) != LINKAGE_OK) {
        return -1;
    }
    for (i = 0; i < STRUTS; i++) {
        joints[i] = legs[i];
        *haldata->correction[i] = corrections[i];
    }
    return 0;
}

KINEMATICS_TYPE kinematicsType(void)
{
    return KINEMATICS_BOTH;
}

/* One kinematics, not switchable (what KINS_NOT_SWITCHABLE declares, without its unused
   parameter warning). */
int kinematicsSwitchable(void)
{
    return 0;
}

int kinematicsSwitch(int switchkins_type)
{
    (void)switchkins_type;
    return 0;
}

EXPORT_SYMBOL(kinematicsSwitchable);
EXPORT_SYMBOL(kinematicsSwitch);
EXPORT_SYMBOL(kinematicsType);
EXPORT_SYMBOL(kinematicsForward);
EXPORT_SYMBOL(kinematicsInverse);

static const double default_base[STRUTS][3] = {
    {DEFAULT_BASE_0_X, DEFAULT_BASE_0_Y, DEFAULT_BASE_0_Z},
    {DEFAULT_BASE_1_X, DEFAULT_BASE_1_Y, DEFAULT_BASE_1_Z},
    {DEFAULT_BASE_2_X, DEFAULT_BASE_2_Y, DEFAULT_BASE_2_Z},
    {DEFAULT_BASE_3_X, DEFAULT_BASE_3_Y, DEFAULT_BASE_3_Z},
    {DEFAULT_BASE_4_X, DEFAULT_BASE_4_Y, DEFAULT_BASE_4_Z},
    {DEFAULT_BASE_5_X, DEFAULT_BASE_5_Y, DEFAULT_BASE_5_Z},
};
static const double default_platform[STRUTS][3] = {
    {DEFAULT_PLATFORM_0_X, DEFAULT_PLATFORM_0_Y, DEFAULT_PLATFORM_0_Z},
    {DEFAULT_PLATFORM_1_X, DEFAULT_PLATFORM_1_Y, DEFAULT_PLATFORM_1_Z},
    {DEFAULT_PLATFORM_2_X, DEFAULT_PLATFORM_2_Y, DEFAULT_PLATFORM_2_Z},
    {DEFAULT_PLATFORM_3_X, DEFAULT_PLATFORM_3_Y, DEFAULT_PLATFORM_3_Z},
    {DEFAULT_PLATFORM_4_X, DEFAULT_PLATFORM_4_Y, DEFAULT_PLATFORM_4_Z},
    {DEFAULT_PLATFORM_5_X, DEFAULT_PLATFORM_5_Y, DEFAULT_PLATFORM_5_Z},
};
static const double default_base_n[STRUTS][3] = {
    {DEFAULT_BASE_0_NX, DEFAULT_BASE_0_NY, DEFAULT_BASE_0_NZ},
    {DEFAULT_BASE_1_NX, DEFAULT_BASE_1_NY, DEFAULT_BASE_1_NZ},
    {DEFAULT_BASE_2_NX, DEFAULT_BASE_2_NY, DEFAULT_BASE_2_NZ},
    {DEFAULT_BASE_3_NX, DEFAULT_BASE_3_NY, DEFAULT_BASE_3_NZ},
    {DEFAULT_BASE_4_NX, DEFAULT_BASE_4_NY, DEFAULT_BASE_4_NZ},
    {DEFAULT_BASE_5_NX, DEFAULT_BASE_5_NY, DEFAULT_BASE_5_NZ},
};
static const double default_platform_n[STRUTS][3] = {
    {DEFAULT_PLATFORM_0_NX, DEFAULT_PLATFORM_0_NY, DEFAULT_PLATFORM_0_NZ},
    {DEFAULT_PLATFORM_1_NX, DEFAULT_PLATFORM_1_NY, DEFAULT_PLATFORM_1_NZ},
    {DEFAULT_PLATFORM_2_NX, DEFAULT_PLATFORM_2_NY, DEFAULT_PLATFORM_2_NZ},
    {DEFAULT_PLATFORM_3_NX, DEFAULT_PLATFORM_3_NY, DEFAULT_PLATFORM_3_NZ},
    {DEFAULT_PLATFORM_4_NX, DEFAULT_PLATFORM_4_NY, DEFAULT_PLATFORM_4_NZ},
    {DEFAULT_PLATFORM_5_NX, DEFAULT_PLATFORM_5_NY, DEFAULT_PLATFORM_5_NZ},
};

static int make_pins(void)
{
    static const char axis[3] = {'x', 'y', 'z'};
    int i, k, r = 0;

    for (i = 0; i < STRUTS; i++) {
        for (k = 0; k < 3; k++) {
            r |= hal_pin_float_newf(HAL_IN, &haldata->base[i][k], comp_id,
                                    "%s.base.%d.%c", prefix, i, axis[k]);
            r |= hal_pin_float_newf(HAL_IN, &haldata->platform[i][k], comp_id,
                                    "%s.platform.%d.%c", prefix, i, axis[k]);
            r |= hal_pin_float_newf(HAL_IN, &haldata->base_n[i][k], comp_id,
                                    "%s.base-n.%d.%c", prefix, i, axis[k]);
            r |= hal_pin_float_newf(HAL_IN, &haldata->platform_n[i][k], comp_id,
                                    "%s.platform-n.%d.%c", prefix, i, axis[k]);
            if (r) return r;
            *haldata->base[i][k] = default_base[i][k];
            *haldata->platform[i][k] = default_platform[i][k];
            *haldata->base_n[i][k] = default_base_n[i][k];
            *haldata->platform_n[i][k] = default_platform_n[i][k];
        }
        r |= hal_pin_float_newf(HAL_OUT, &haldata->correction[i], comp_id,
                                "%s.correction.%d", prefix, i);
        if (r) return r;
        *haldata->correction[i] = 0.0;
    }
    r |= hal_pin_float_newf(HAL_IN, &haldata->screw_lead, comp_id, "%s.screw-lead", prefix);
    r |= hal_pin_float_newf(HAL_IN, &haldata->spindle_offset, comp_id, "%s.spindle-offset", prefix);
    r |= hal_pin_float_newf(HAL_IN, &haldata->tool_offset, comp_id, "%s.tool-offset", prefix);
    r |= hal_pin_float_newf(HAL_IN, &haldata->conv_criterion, comp_id,
                            "%s.convergence-criterion", prefix);
    r |= hal_pin_float_newf(HAL_IN, &haldata->max_error, comp_id, "%s.max-error", prefix);
    r |= hal_pin_u32_newf(HAL_IN, &haldata->iter_limit, comp_id, "%s.limit-iterations", prefix);
    r |= hal_pin_u32_newf(HAL_OUT, &haldata->last_iter, comp_id, "%s.last-iterations", prefix);
    r |= hal_pin_u32_newf(HAL_OUT, &haldata->max_iter, comp_id, "%s.max-iterations", prefix);
    r |= hal_pin_bit_newf(HAL_OUT, &haldata->fwd_kins_fail, comp_id, "%s.fwd-kins-fail", prefix);
    r |= hal_pin_s32_newf(HAL_OUT, &haldata->status, comp_id, "%s.status", prefix);
    r |= hal_pin_bit_newf(HAL_OUT, &haldata->refused, comp_id, "%s.refused", prefix);
    r |= hal_pin_u32_newf(HAL_OUT, &haldata->refusals, comp_id, "%s.refusals", prefix);
    r |= hal_pin_u32_newf(HAL_OUT, &haldata->failures, comp_id, "%s.failures", prefix);
    r |= hal_pin_s32_newf(HAL_OUT, &haldata->last_failure, comp_id, "%s.last-failure", prefix);
    r |= hal_pin_bit_newf(HAL_OUT, &haldata->tracking, comp_id, "%s.tracking", prefix);
    r |= hal_pin_float_newf(HAL_OUT, &haldata->proximity, comp_id, "%s.proximity", prefix);
    r |= hal_pin_float_newf(HAL_OUT, &haldata->min_proximity, comp_id, "%s.min-proximity", prefix);
    r |= hal_pin_bit_newf(HAL_OUT, &haldata->fell_back, comp_id, "%s.fell-back", prefix);
    r |= hal_pin_bit_newf(HAL_IN, &haldata->reset, comp_id, "%s.reset", prefix);
    r |= hal_pin_bit_newf(HAL_IN, &haldata->certify, comp_id, "%s.certify", prefix);
    r |= hal_pin_bit_newf(HAL_OUT, &haldata->certified, comp_id, "%s.certified", prefix);
    if (r) return r;
    *haldata->screw_lead = DEFAULT_SCREW_LEAD;
    *haldata->spindle_offset = 0.0;
    *haldata->tool_offset = 0.0;
    *haldata->conv_criterion = 1e-9;
    *haldata->max_error = 500.0;
    *haldata->iter_limit = 120;
    *haldata->last_iter = 0;
    *haldata->max_iter = 0;
    *haldata->fwd_kins_fail = 0;
    *haldata->status = 0;
    *haldata->refused = 0;
    *haldata->refusals = 0;
    *haldata->failures = 0;
    *haldata->certify = 0;
    *haldata->certified = 0;
    *haldata->last_failure = 0;
    *haldata->tracking = 0;
    *haldata->proximity = 0.0;
    *haldata->min_proximity = 0.0;
    *haldata->fell_back = 0;
    *haldata->reset = 0;
    return 0;
}

int rtapi_app_main(void)
{
    int i, k, rc;

    if (linkage_hexapod_size() > sizeof hex) {
        rtapi_print_msg(RTAPI_MSG_ERR, "linkagehexkins: handle needs %lu bytes, header gives %lu\n",
                        (unsigned long)linkage_hexapod_size(), (unsigned long)sizeof hex);
        return -1;
    }
    comp_id = hal_init("linkagehexkins");
    if (comp_id < 0) {
        return comp_id;
    }
    haldata = hal_malloc(sizeof *haldata);
    if (!haldata || make_pins() != 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "linkagehexkins: cannot create pins\n");
        hal_exit(comp_id);
        return -1;
    }
    for (i = 0; i < STRUTS; i++) {
        for (k = 0; k < 3; k++) {
            current.base[i][k] = default_base[i][k];
            current.platform[i][k] = default_platform[i][k];
        }
    }
    rc = linkage_hexapod_init(&hex, &current);
    if (rc != LINKAGE_OK) {
        rtapi_print_msg(RTAPI_MSG_ERR, "linkagehexkins: %s\n", linkage_status_name(rc));
        hal_exit(comp_id);
        return -1;
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    hal_exit(comp_id);
}
