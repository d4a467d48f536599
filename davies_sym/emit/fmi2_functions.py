"""The FMI 2.0 co-simulation functions every unit shares (`davies_sym.emit.fmu_sources`),
as C text: instantiation, the getters and setters of the parameters, inputs and outputs,
the step, and the optional functions a unit without states answers with an error.  The
placeholders ``@GUID@``, ``@STARTS@`` and ``@RESET@`` are the unit's own (its GUID, and the
assignments of the parameters' start values); the unit's own part defines ``REASONS``,
``rest`` (the signs remembered for the limits at zero speed, before any motion) and
``compute`` (the outputs ``y`` of the inputs ``u`` and the parameters ``p``)."""

FMI_FUNCTIONS = r"""static void say(Instance *c, fmi2Status status, const char *category, const char *message) {
    if (c->callbacks.logger != NULL) {
        c->callbacks.logger(c->callbacks.componentEnvironment, c->name, status, category, "%s", message);
    }
}

static fmi2Status report(Instance *c) {
    if (c->status == 0) {
        return fmi2OK;
    }
    say(c, fmi2Warning, "logStatusWarning", REASONS[c->status < 0 || c->status >= STATUSES ? 2 : c->status]);
    return fmi2Warning;
}

FMI_EXPORT const char *fmi2GetTypesPlatform(void) { return "default"; }
FMI_EXPORT const char *fmi2GetVersion(void) { return "2.0"; }

FMI_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String categories[]) {
    (void)n;
    (void)categories;
    ((Instance *)c)->logging = on;
    return fmi2OK;
}

FMI_EXPORT fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid, fmi2String location,
                                         const fmi2CallbackFunctions *callbacks, fmi2Boolean visible,
                                         fmi2Boolean logging) {
    Instance *c;
    (void)location;
    (void)visible;
    if (type != fmi2CoSimulation || guid == NULL || strcmp(guid, "@GUID@") != 0) {
        return NULL;
    }
    c = (Instance *)calloc(1, sizeof(Instance));
    if (c == NULL) {
        return NULL;
    }
    c->name = (char *)malloc(strlen(name ? name : "") + 1);
    if (c->name != NULL) {
        strcpy(c->name, name ? name : "");
    }
    if (callbacks != NULL) {
        c->callbacks = *callbacks;
    }
    c->logging = logging;
@STARTS@
    rest(c);
    compute(c);
    return c;
}

FMI_EXPORT void fmi2FreeInstance(fmi2Component c) {
    if (c != NULL) {
        free(((Instance *)c)->name);
        free(c);
    }
}

FMI_EXPORT fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                                          fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    (void)toleranceDefined;
    (void)tolerance;
    (void)stopTimeDefined;
    (void)stopTime;
    ((Instance *)c)->time = startTime;
    return fmi2OK;
}

FMI_EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }

FMI_EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    compute((Instance *)c);
    return report((Instance *)c);
}

FMI_EXPORT fmi2Status fmi2Terminate(fmi2Component c) { (void)c; return fmi2OK; }

FMI_EXPORT fmi2Status fmi2Reset(fmi2Component c) {
    Instance *i = (Instance *)c;
@RESET@
    memset(i->u, 0, sizeof i->u);
    rest(i);
    compute(i);
    return fmi2OK;
}

FMI_EXPORT fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real value[]) {
    Instance *i = (Instance *)c;
    size_t k;
    compute(i);
    for (k = 0; k < n; k++) {
        unsigned int r = vr[k];
        if (r < PARAMETERS) {
            value[k] = i->p[r];
        } else if (r < FIRST_OUTPUT) {
            value[k] = i->u[r - FIRST_INPUT];
        } else if (r < REALS) {
            value[k] = i->y[r - FIRST_OUTPUT];
        } else {
            return fmi2Error;
        }
    }
    return fmi2OK;
}

FMI_EXPORT fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real value[]) {
    Instance *i = (Instance *)c;
    size_t k;
    for (k = 0; k < n; k++) {
        unsigned int r = vr[k];
        if (r < PARAMETERS) {
            i->p[r] = value[k];
        } else if (r < FIRST_OUTPUT) {
            i->u[r - FIRST_INPUT] = value[k];
        } else {
            return fmi2Error;
        }
    }
    return fmi2OK;
}

FMI_EXPORT fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer value[]) {
    Instance *i = (Instance *)c;
    size_t k;
    compute(i);
    for (k = 0; k < n; k++) {
        if (vr[k] == 0) {
            value[k] = i->variant;
        } else if (vr[k] == 1) {
            value[k] = i->status;
        } else {
            return fmi2Error;
        }
    }
    return fmi2OK;
}

FMI_EXPORT fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer v[]) {
    (void)c; (void)vr; (void)v;
    return n == 0 ? fmi2OK : fmi2Error;
}

FMI_EXPORT fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean v[]) {
    (void)c; (void)vr; (void)v;
    return n == 0 ? fmi2OK : fmi2Error;
}

FMI_EXPORT fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Boolean v[]) {
    (void)c; (void)vr; (void)v;
    return n == 0 ? fmi2OK : fmi2Error;
}

FMI_EXPORT fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String v[]) {
    (void)c; (void)vr; (void)v;
    return n == 0 ? fmi2OK : fmi2Error;
}

FMI_EXPORT fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2String v[]) {
    (void)c; (void)vr; (void)v;
    return n == 0 ? fmi2OK : fmi2Error;
}

FMI_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)c; (void)s; return fmi2Error; }
FMI_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) { (void)c; (void)s; return fmi2Error; }
FMI_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)c; (void)s; return fmi2Error; }
FMI_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *n) {
    (void)c; (void)s; (void)n;
    return fmi2Error;
}
FMI_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n) {
    (void)c; (void)s; (void)b; (void)n;
    return fmi2Error;
}
FMI_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s) {
    (void)c; (void)b; (void)n; (void)s;
    return fmi2Error;
}
FMI_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                                   const fmi2ValueReference z[], size_t nz, const fmi2Real dv[],
                                                   fmi2Real dz[]) {
    (void)c; (void)u; (void)nu; (void)z; (void)nz; (void)dv; (void)dz;
    return fmi2Error;
}
FMI_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                                  const fmi2Integer order[], const fmi2Real value[]) {
    (void)c; (void)vr; (void)n; (void)order; (void)value;
    return fmi2Error;
}
FMI_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                                   const fmi2Integer order[], fmi2Real value[]) {
    (void)c; (void)vr; (void)n; (void)order; (void)value;
    return fmi2Error;
}

FMI_EXPORT fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean keepsNoState) {
    Instance *i = (Instance *)c;
    (void)keepsNoState;
    i->time = t + h;
    compute(i);
    return report(i);
}

FMI_EXPORT fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2Error; }

FMI_EXPORT fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *v) {
    (void)c; (void)s; (void)v;
    return fmi2Discard;
}
FMI_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *v) {
    if (s != fmi2LastSuccessfulTime) {
        return fmi2Discard;
    }
    *v = ((Instance *)c)->time;
    return fmi2OK;
}
FMI_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *v) {
    (void)c; (void)s; (void)v;
    return fmi2Discard;
}
FMI_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *v) {
    (void)c; (void)s; (void)v;
    return fmi2Discard;
}
FMI_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *v) {
    (void)c; (void)s; (void)v;
    return fmi2Discard;
}
"""
