#!/usr/bin/env python3
"""Symbolic check of physics.md §13 (anisotropic inertia) and its worked example W7.

Run: python3 docs/physics_inertia_check.py   (needs python3-sympy; exits non-zero on a failed check)

Checks, exactly (sympy simplification to 0):
  1. ½ g(De_A/Dt, De_B/Dt) J^{AB} = ½ tr(M J Mᵀ) with M = L̇ + Cφ̇εL (orthonormal frame, §1, §3);
  2. the Legendre transform: P = ∂T/∂L̇ = MJ, p_φ = mS²φ̇ + C tr((εL)ᵀP), and
     H = p·q̇ − T + V = p_r²/2m + (p_φ − Cs)²/(2mS²) + ½tr(PJ⁻¹Pᵀ) + V, s = tr((εL)ᵀP);
  3. Hamilton's equations L̇ = PJ⁻¹ − Cφ̇εL, Ṗ = −∂V/∂L − Cφ̇εP (same form as §4 with P/J → PJ⁻¹);
  4. {s, H} = 0 for V = V(LᵀL), any J (left rotations commute with J);
     {p_β, H} = 0 for V = V(‖L‖², det L) and isotropic J; {p_β, T_int} ≠ 0 for an anisotropic J;
  5. rigid reduction: L = λ₀U(θ), M = ωεL gives T_int = ½ω²λ₀² tr J (the isotropic body with tr(J)/2);
  6. W7: the numbers quoted in physics.md §13 (also asserted by tests/engine/anisotropic_inertia_test.cpp).
"""
import sys

import sympy as sp

ok = True


def check(name, expr):
    global ok
    e = sp.simplify(sp.expand(expr))
    good = e == 0
    ok &= good
    print(("ok    " if good else "FAIL  ") + name + ("" if good else f": {e}"))


m, R = sp.symbols("m R", positive=True)
r, phi, rd, phid = sp.symbols("r phi rdot phidot", real=True)
J11, J12, J22 = sp.symbols("J11 J12 J22", real=True)
Jm = sp.Matrix([[J11, J12], [J12, J22]])
eps = sp.Matrix([[0, -1], [1, 0]])
L = sp.Matrix(2, 2, sp.symbols("L11 L12 L21 L22", real=True))
Ld = sp.Matrix(2, 2, sp.symbols("Ld11 Ld12 Ld21 Ld22", real=True))
P = sp.Matrix(2, 2, sp.symbols("P11 P12 P21 P22", real=True))
S, C = R * sp.sin(r / R), sp.cos(r / R)  # the sphere; the algebra does not depend on S, C
pr, pphi = sp.symbols("p_r p_phi", real=True)

# 1. kinetic energy: De_A/Dt = E_B M_BA, g(E_A, E_B) = δ_AB ⇒ g(De_A, De_B) = (MᵀM)_AB.
M = Ld + C * phid * eps * L
T_int_def = sp.Rational(1, 2) * sum(Jm[a, b] * (M.T * M)[a, b] for a in range(2) for b in range(2))
check("T_int = 1/2 tr(M J M^T)", T_int_def - sp.Rational(1, 2) * (M * Jm * M.T).trace())

# 2. Legendre transform.
T = m / 2 * (rd**2 + S**2 * phid**2) + T_int_def
Pd = sp.Matrix(2, 2, lambda i, j: sp.diff(T, Ld[i, j]))
check("P = M J", (Pd - M * Jm).norm() ** 2)
s_of = lambda L_, P_: sum((eps * L_).multiply_elementwise(P_))  # tr((εL)ᵀP)
check("p_phi = m S^2 phidot + C s", sp.diff(T, phid) - (m * S**2 * phid + C * s_of(L, M * Jm)))
Jinv = Jm.inv()


def H_of(pr_, pphi_, L_, P_):
    s = s_of(L_, P_)
    return pr_**2 / (2 * m) + (pphi_ - C * s) ** 2 / (2 * m * S**2) + sp.Rational(1, 2) * (P_ * Jinv * P_.T).trace()


legendre = (m * rd) * rd + sp.diff(T, phid) * phid + sum(Pd[i, j] * Ld[i, j] for i in range(2) for j in range(2)) - T
check("H(p(qdot)) = p.qdot - T", H_of(m * rd, sp.diff(T, phid), L, M * Jm) - legendre)

# 3. Hamilton's equations with a general V(L) (a symbolic function of the four entries).
V = sp.Function("V")(*L)
H = H_of(pr, pphi, L, P) + V
s = s_of(L, P)
phid_H = (pphi - C * s) / (m * S**2)
Ldot = sp.Matrix(2, 2, lambda i, j: sp.diff(H, P[i, j]))
Pdot = sp.Matrix(2, 2, lambda i, j: -sp.diff(H, L[i, j]))
dVdL = sp.Matrix(2, 2, lambda i, j: sp.diff(V, L[i, j]))
check("Ldot = P J^-1 - C phidot eps L", (Ldot - (P * Jinv - C * phid_H * eps * L)).norm() ** 2)
check("Pdot = -dV/dL - C phidot eps P", (Pdot - (-dVdL - C * phid_H * eps * P)).norm() ** 2)

# 4. Symmetries: V depends on LᵀL only (a, b, c its entries).
a_, b_, c_ = sp.symbols("a b c", real=True)
W = sp.Function("W")
G = L.T * L
Vg = W(G[0, 0], G[0, 1], G[1, 1])
Hg = H_of(pr, pphi, L, P) + Vg


def bracket(f, g):  # canonical in (L, P); f, g here do not involve r, φ
    return sum(sp.diff(f, L[i, j]) * sp.diff(g, P[i, j]) - sp.diff(f, P[i, j]) * sp.diff(g, L[i, j])
               for i in range(2) for j in range(2))


p_beta = -sum((L * eps).multiply_elementwise(P))  # −tr((Lε)ᵀP)
check("{s, H} = 0 for V(L^T L), any J", bracket(s, Hg))
iso = {J12: 0, J22: J11}
# p_β generates right rotations L → LU(θ)ᵀ: it needs V invariant under them too, V(‖L‖², det L) = V(x², y²)
# (every potential of §5), as well as isotropic J.
Vxy = W(G.trace(), L.det(), 0)
check("{p_beta, H} = 0 for V(|L|^2, det L), isotropic J", bracket(p_beta, H_of(pr, pphi, L, P) + Vxy).subs(iso))
# Anisotropic: {p_β, H} = {p_β, ½tr(PJ⁻¹Pᵀ)} (V(LᵀL) is right-invariant only through LᵀL → UᵀLᵀLU,
# which it is not in general either; the kinetic part alone already fails): nonzero at a state.
kin = sp.Rational(1, 2) * (P * Jinv * P.T).trace()
val = bracket(p_beta, kin).subs({J11: 2, J12: sp.Rational(1, 2), J22: 1, P[0, 0]: 1, P[0, 1]: 0, P[1, 0]: 0,
                                 P[1, 1]: 0, L[0, 0]: 1, L[0, 1]: 0, L[1, 0]: 0, L[1, 1]: 1})
good = sp.simplify(val) != 0
ok &= good
print(("ok    " if good else "FAIL  ") + f"{{p_beta, T_int}} != 0 for anisotropic J (= {sp.nsimplify(val)} at a state)")

# 5. Rigid reduction.
lam0, th, om = sp.symbols("lambda0 theta omega", real=True)
U = sp.Matrix([[sp.cos(th), -sp.sin(th)], [sp.sin(th), sp.cos(th)]])
Lr = lam0 * U
Mr = om * eps * Lr
check("rigid: 1/2 tr(M J M^T) = 1/2 w^2 lambda0^2 tr J",
      sp.Rational(1, 2) * (Mr * Jm * Mr.T).trace() - sp.Rational(1, 2) * om**2 * lam0**2 * Jm.trace())

# 6. Worked example W7 (sphere R = 1, m = 2, no potential; J = [[0.3, 0.05], [0.05, 0.1]]).
W7 = {m: 2, R: 1, J11: sp.Rational(3, 10), J12: sp.Rational(1, 20), J22: sp.Rational(1, 10)}
Lv = sp.Matrix([[sp.Rational(3, 2), sp.Rational(1, 5)], [-sp.Rational(1, 10), sp.Rational(1, 2)]])
Mv = sp.Matrix([[sp.Rational(1, 10), sp.Rational(3, 10)], [-sp.Rational(2, 5), sp.Rational(1, 5)]])
rv, phiv, rdv, phidv = 1, sp.Rational(1, 2), sp.Rational(1, 5), -sp.Rational(3, 10)
sub = dict(W7)
sub.update({r: rv, rd: rdv, phid: phidv})
Pv = (Mv * Jm).subs(sub)
sv = s_of(Lv, Pv)
pphiv = (m * S**2 * phid + C * sv).subs(sub)
Hv = H_of(m * rd, pphiv, Lv, Pv).subs(sub)
pbv = -sum((Lv * eps).multiply_elementwise(Pv))
subs_state = dict(W7)
subs_state.update({r: rv, pr: (m * rd).subs(sub), pphi: pphiv})
subs_state.update({L[i, j]: Lv[i, j] for i in range(2) for j in range(2)})
subs_state.update({P[i, j]: Pv[i, j] for i in range(2) for j in range(2)})
H0 = H_of(pr, pphi, L, P)
Ldot0 = sp.Matrix(2, 2, lambda i, j: sp.diff(H0, P[i, j])).subs(subs_state)
print("W7: H =", sp.N(Hv, 17), " s =", sp.N(sv, 17), " p_beta =", sp.N(pbv, 17), " p_phi =", sp.N(pphiv, 17))
print("W7: dL/dt =", [sp.N(v, 17) for v in Ldot0])
print("W7: {p_beta, H} =", sp.N(bracket(p_beta, H0).subs(subs_state), 17))
sys.exit(0 if ok else 1)
