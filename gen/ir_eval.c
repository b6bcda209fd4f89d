/* ir_eval.c — single-precision semantics of the IR's arithmetic, as GLSL
 * defines them: every operation rounded to float, no fused multiply-add,
 * float operands broadcast against vectors. */
#include <limits.h>
#include <math.h>

#include "ir_eval.h"

/* Component k of a float operand, broadcasting a scalar. */
static inline float comp(const scg_reg *r, scg_type t, int k)
{
    return t == SCG_FLOAT ? r->f[0] : r->f[k];
}

static float dotf(const float *x, const float *y, int w)
{
    float s = x[0] * y[0];
    for (int k = 1; k < w; k++)
        s = s + x[k] * y[k];
    return s;
}

/* One case per op with SCG_OPF_EVAL in the op table (ops.h). */
void scg_eval_arith(const scg_inst *in, const scg_reg *ops, const scg_type *types,
                    scg_reg *out)
{
    const scg_reg *a = &ops[0], *b = &ops[1], *c = &ops[2];
    int w = scg_type_width(in->type);
    bool ints = types[0] == SCG_INT;
    switch (in->op) {
    case SCG_OP_ADD:
        if (ints) out->i[0] = (int)((unsigned)a->i[0] + (unsigned)b->i[0]);
        else for (int k = 0; k < w; k++) out->f[k] = comp(a, types[0], k) + comp(b, types[1], k);
        break;
    case SCG_OP_SUB:
        if (ints) out->i[0] = (int)((unsigned)a->i[0] - (unsigned)b->i[0]);
        else for (int k = 0; k < w; k++) out->f[k] = comp(a, types[0], k) - comp(b, types[1], k);
        break;
    case SCG_OP_MUL:
        if (ints) out->i[0] = (int)((unsigned)a->i[0] * (unsigned)b->i[0]);
        else for (int k = 0; k < w; k++) out->f[k] = comp(a, types[0], k) * comp(b, types[1], k);
        break;
    case SCG_OP_DIV:
        if (ints) out->i[0] = b->i[0] == 0 || (b->i[0] == -1 && a->i[0] == INT_MIN) ? 0
                                                                           : a->i[0] / b->i[0];
        else for (int k = 0; k < w; k++) out->f[k] = comp(a, types[0], k) / comp(b, types[1], k);
        break;
    case SCG_OP_NEG:
        if (ints) out->i[0] = (int)(0u - (unsigned)a->i[0]);
        else for (int k = 0; k < w; k++) out->f[k] = -a->f[k];
        break;
    case SCG_OP_MIN:
        if (ints) out->i[0] = b->i[0] < a->i[0] ? b->i[0] : a->i[0];
        else for (int k = 0; k < w; k++) {
            float x = comp(a, types[0], k), y = comp(b, types[1], k);
            out->f[k] = y < x ? y : x;
        }
        break;
    case SCG_OP_MAX:
        if (ints) out->i[0] = a->i[0] < b->i[0] ? b->i[0] : a->i[0];
        else for (int k = 0; k < w; k++) {
            float x = comp(a, types[0], k), y = comp(b, types[1], k);
            out->f[k] = x < y ? y : x;
        }
        break;
    case SCG_OP_ABS:
        if (ints) out->i[0] = a->i[0] < 0 ? (int)(0u - (unsigned)a->i[0]) : a->i[0];
        else for (int k = 0; k < w; k++) out->f[k] = fabsf(a->f[k]);
        break;
    case SCG_OP_SQRT:
        for (int k = 0; k < w; k++) out->f[k] = sqrtf(a->f[k]);
        break;
    case SCG_OP_FLOOR:
        for (int k = 0; k < w; k++) out->f[k] = floorf(a->f[k]);
        break;
    case SCG_OP_DOT:
        out->f[0] = dotf(a->f, b->f, scg_type_width(types[0]));
        break;
    case SCG_OP_CROSS: {
        float x = a->f[1] * b->f[2] - a->f[2] * b->f[1];
        float y = a->f[2] * b->f[0] - a->f[0] * b->f[2];
        float z = a->f[0] * b->f[1] - a->f[1] * b->f[0];
        out->f[0] = x; out->f[1] = y; out->f[2] = z;
        break;
    }
    case SCG_OP_LENGTH:
        out->f[0] = sqrtf(dotf(a->f, a->f, scg_type_width(types[0])));
        break;
    case SCG_OP_VEC:
        for (int k = 0; k < w; k++) out->f[k] = ops[k].f[0];
        break;
    case SCG_OP_COMP:
        out->f[0] = a->f[in->slot];
        break;
    case SCG_OP_LT: out->i[0] = ints ? a->i[0] < b->i[0] : a->f[0] < b->f[0]; break;
    case SCG_OP_LE: out->i[0] = ints ? a->i[0] <= b->i[0] : a->f[0] <= b->f[0]; break;
    case SCG_OP_EQ: out->i[0] = ints ? a->i[0] == b->i[0] : a->f[0] == b->f[0]; break;
    case SCG_OP_NE: out->i[0] = ints ? a->i[0] != b->i[0] : a->f[0] != b->f[0]; break;
    case SCG_OP_AND: out->i[0] = a->i[0] && b->i[0]; break;
    case SCG_OP_OR: out->i[0] = a->i[0] || b->i[0]; break;
    case SCG_OP_NOT: out->i[0] = !a->i[0]; break;
    case SCG_OP_SELECT:
        *out = a->i[0] ? *b : *c;
        break;
    case SCG_OP_I2F:
        out->f[0] = (float)a->i[0];
        break;
    case SCG_OP_F2I: {
        /* GLSL leaves out-of-range conversions undefined; 0 keeps C defined. */
        float x = a->f[0];
        out->i[0] = x > -2147483520.0f && x < 2147483520.0f ? (int)x : 0;
        break;
    }
    default:
        break;
    }
}
