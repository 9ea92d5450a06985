"""The one label table of invasim's figures (scripts/plot_run.py, scripts/master_curve.py):
human names, symbols and units for the columns of series.csv and results.csv and for the
state-point keys of a sweep, so that no figure shows a raw column name such as
`phi_a_local_std`. Python standard library only.

label(name)            -> "$\\Delta\\phi_a$ (std of the local adipocyte packing fraction)"
symbol(name)           -> "$\\Delta\\phi_a$"
unit_text(unit)        -> "[$\\sigma^2$]" for "sigma^2", "(dimensionless)" for "" or "1"
axis_label(text, unit) -> "interfacial area [$\\sigma^2$]"
state_label({"beta": "0.01", "tau_p": "25"}) -> "$\\beta$ = 0.01, $\\tau_p$ = 25"
raw_names(text)        -> the raw column names (words with an underscore outside $...$) in
                          a label; a figure's labels must give none.
An unknown name is a LabelError naming it: add it to QUANTITIES rather than print it raw.
"""

import re


class LabelError(KeyError):
    """A column or key without an entry in the label table."""

    def __str__(self):
        return self.args[0]


# name -> (symbol (matplotlib mathtext), what it is). Columns of series.csv (thermo, interface
# observers), summary/results columns, and sweep state-point keys.
QUANTITIES = {
    "time": (r"$t$", "time"),
    "step": ("step", "completed steps"),
    "T_c": (r"$k_B T_c$", "cancer cells"),
    "T_a": (r"$k_B T_a$", "adipocyte vertices"),
    "T_c_over_T_a": (r"$T_c/T_a$", "temperature ratio"),
    "kT_c_paper": (r"$2 k_B T_c$", "the paper's convention"),
    "P_left": (r"$P_\mathrm{left}$", "on the left wall"),
    "P_right": (r"$P_\mathrm{right}$", "on the right wall"),
    "L_x": (r"$L_x$", "distance between the walls"),
    "phi": (r"$\phi$", "all cells"),
    "phi_c": (r"$\phi_c$", "cancer cells"),
    "phi_a": (r"$\phi_a$", "adipocytes"),
    "phi_a_local_mean": (r"$\langle\phi_a^\mathrm{local}\rangle$",
                         "mean local adipocyte packing fraction"),
    "phi_a_local_std": (r"$\Delta\phi_a$", "std of the local adipocyte packing fraction"),
    "A_t": (r"$A_t$", "cancer-adipocyte interface"),
    "A_t_max": (r"$A_t^\mathrm{max}$", "fully invaded bound"),
    "A_ratio": (r"$A_t/A_t^\mathrm{max}$", "degree of invasion"),
    "A_wall_a": (r"$A_\mathrm{wall,a}$", "adipocyte area on the walls"),
    "A_n": (r"$A_n$", "normalised interfacial area"),
    "N_c": (r"$N_c$", "cancer cells"),
    "V0_ratio": (r"$v_0/v_0^\mathrm{initial}$", "mean over the adipocytes"),
    "N_touched": (r"$N_\mathrm{touched}$", "adipocytes touched"),
    "tau_d": (r"$\tau_d$", "velocity decorrelation time"),
    "tau_r": (r"$\tau_r$", "structural relaxation time"),
    # sweep state-point keys
    "kT": (r"$k_B T$", "background temperature"),
    "beta": (r"$\beta$", "cohesion"),
    "tau_p": (r"$\tau_p$", "persistence time"),
    "f0": (r"$f_0$", "active force"),
    "P": (r"$P$", "pressure"),
    "K_ecm": (r"$K_\mathrm{ecm}$", "tether stiffness"),
    "lambda": (r"$\lambda$", "tether heterogeneity"),
    "A_0": (r"$\mathcal{A}_0$", "reference shape parameter"),
    "phi_a_target": (r"$\phi_a^\mathrm{target}$", "target adipocyte packing fraction"),
    "seed": ("seed", "replicate"),
    "gamma": (r"$\gamma$", "damping"),
}

# The units series.csv and results.csv write (`name [unit]`), as figure text.
UNITS = {
    "tau": r"$\tau$",
    "sigma": r"$\sigma$",
    "sigma^2": r"$\sigma^2$",
    "sigma^3": r"$\sigma^3$",
    "eps_c": r"$\epsilon_c$",
    "eps_c/sigma^3": r"$\epsilon_c/\sigma^3$",
    "eps_c/sigma": r"$\epsilon_c/\sigma$",
}
DIMENSIONLESS = ("", "1")


def _entry(name):
    if name in QUANTITIES:
        return QUANTITIES[name]
    m = re.fullmatch(r"E_(\w+)", name)  # energy terms: E_total, E_contact, ...
    if m:
        return (r"$E_\mathrm{%s}$" % m.group(1).replace("_", r"\_"), "energy")
    m = re.fullmatch(r"(\w+?)_(error|drift)", name)  # results.csv companions
    if m and (m.group(1) in QUANTITIES or m.group(1).startswith("E_")):
        base = _entry(m.group(1))
        return (base[0], "%s of %s" % ("error" if m.group(2) == "error" else "drift", base[1]))
    raise LabelError("no label for '%s': add it to QUANTITIES in scripts/invasim_analysis/plot_labels.py"
                     % name)


def symbol(name):
    return _entry(name)[0]


def label(name):
    """Symbol and description: "$T_c$ (cancer cells)"."""
    sym, what = _entry(name)
    return "%s (%s)" % (sym, what) if what and sym != what else sym


def unit_text(unit):
    """"[$\\sigma^2$]" for sigma^2, "(dimensionless)" for no unit; unknown units verbatim."""
    unit = (unit or "").strip()
    if unit in DIMENSIONLESS:
        return "(dimensionless)"
    return "[%s]" % UNITS.get(unit, unit)


def axis_label(text, unit):
    return "%s %s" % (text, unit_text(unit))


def state_label(assignments):
    """"$\\beta$ = 0.01, $\\tau_p$ = 25" for {"beta": "0.01", "tau_p": "25"} (dict or pairs)."""
    items = assignments.items() if hasattr(assignments, "items") else assignments
    return ", ".join("%s = %s" % (symbol(k), v) for k, v in items) or "all"


def raw_names(text):
    """Words with an underscore outside mathtext ($...$): raw column names in a label."""
    plain = re.sub(r"\$[^$]*\$", " ", text or "")
    return re.findall(r"[A-Za-z]\w*_\w+", plain)
