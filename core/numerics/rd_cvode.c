/*
 * rd_cvode.c — the CVODE session of ringdyn's integrators (rd_cvode.h).
 */
#include "rd_cvode.h"

#include <stdio.h>

static void silent(int code, const char *module, const char *function, char *msg, void *user)
{
    (void)code;
    (void)module;
    (void)function;
    rd_cvode *s = user;
    snprintf(s->msg, sizeof s->msg, "%s", msg ? msg : "");
}

int rd_cvode_open(rd_cvode *s, double deg_per_s, rd_error *err)
{
    s->deg_per_s = deg_per_s;
    s->msg[0] = '\0';
    if (SUNContext_Create(NULL, &s->ctx)) {
        s->ctx = NULL;
        return rd_error_set(err, RD_ENOMEM, "", "Could not create the SUNDIALS context.");
    }
    return RD_OK;
}

int rd_cvode_create(rd_cvode *s, rd_error *err)
{
    s->cv = CVodeCreate(CV_BDF, s->ctx);
    if (!s->cv)
        return rd_error_set(err, RD_ENOMEM, "", "Out of memory creating the CVODE solver.");
    int flag = CVodeSetErrHandlerFn(s->cv, silent, s);
    return flag ? rd_cvode_misuse(s, flag, "set-up", err) : RD_OK;
}

void rd_cvode_close(rd_cvode *s)
{
    if (s->cv)
        CVodeFree(&s->cv);
    s->cv = NULL;
}

void rd_cvode_close_context(rd_cvode *s)
{
    if (s->ctx)
        SUNContext_Free(&s->ctx);
    s->ctx = NULL;
}

int rd_cvode_misuse(const rd_cvode *s, int flag, const char *what, rd_error *err)
{
    return rd_error_set(err, RD_EINTERNAL, "", "CVODE %s failed: %s (%s).", what,
                        CVodeGetReturnFlagName(flag), s->msg);
}

const char *rd_cvode_flag_words(int flag)
{
    switch (flag) {
    case CV_TOO_MUCH_WORK:
        return "the step budget was used up";
    case CV_TOO_MUCH_ACC:
        return "the requested accuracy is below what double precision allows";
    case CV_ERR_FAILURE:
        return "the error test failed repeatedly (the step size collapsed)";
    case CV_CONV_FAILURE:
        return "the Newton iteration failed to converge repeatedly";
    case CV_LSETUP_FAIL:
    case CV_LSOLVE_FAIL:
        return "the linear solver failed (singular Newton matrix)";
    case CV_RHSFUNC_FAIL:
    case CV_REPTD_RHSFUNC_ERR:
    case CV_UNREC_RHSFUNC_ERR:
    case CV_FIRST_RHSFUNC_ERR:
        return "the forces became non-finite";
    case CV_TOO_CLOSE:
        return "the output times are too close together";
    default:
        return "the integrator failed";
    }
}

int rd_cvode_failure(const rd_cvode *s, int flag, double t, const rd_cvode_limit *lim,
                     rd_error *err)
{
    double deg = t * s->deg_per_s;
    if (flag == CV_TOO_MUCH_WORK)
        return rd_error_set(err, RD_ELIMIT, "/max_steps",
                            "The integration used its @/max_steps = %ld steps by crank "
                            "angle %.3f deg (of %.1f): the %s needs more work than "
                            "allowed; raise max_steps, or make the run cheaper: fewer cycles, a "
                            "cheaper model (/numerics/model) or a looser /numerics/rtol.",
                            lim->max_steps, deg, lim->total_deg, lim->motion);
    return rd_error_set(err, RD_ENOCONV, "",
                        "The %s integration failed at crank angle %.4f deg after %ld steps: "
                        "%s (CVODE %s: %s).",
                        lim->analysis, deg, lim->steps, rd_cvode_flag_words(flag),
                        CVodeGetReturnFlagName(flag), s->msg);
}

int rd_cvode_counters(const rd_cvode *s, long c[RD_CVODE_COUNTERS])
{
    int flag;
    if ((flag = CVodeGetNumSteps(s->cv, &c[0])) || (flag = CVodeGetNumRhsEvals(s->cv, &c[1])) ||
        (flag = CVodeGetNumJacEvals(s->cv, &c[2])) ||
        (flag = CVodeGetNumLinSolvSetups(s->cv, &c[3])) ||
        (flag = CVodeGetNumNonlinSolvIters(s->cv, &c[4])) ||
        (flag = CVodeGetNumNonlinSolvConvFails(s->cv, &c[5])) ||
        (flag = CVodeGetNumErrTestFails(s->cv, &c[6])) || (flag = CVodeGetNumGEvals(s->cv, &c[7])))
        return flag;
    return 0;
}

SUNLinearSolver rd_linsol_wrap(SUNContext ctx, void *content,
                               const struct _generic_SUNLinearSolver_Ops *ops)
{
    SUNLinearSolver LS = content ? SUNLinSolNewEmpty(ctx) : NULL;
    if (!LS)
        return NULL;
    *LS->ops = *ops;
    LS->content = content;
    return LS;
}
