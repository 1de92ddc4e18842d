# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # Chung & Ooi's benchmark tests, exact
#
# Every DEM code verifies its contact model on the eight impact tests of Chung & Ooi (Granular Matter 13, 2011,
# 643–656): normal impacts of two spheres and of a sphere on a plane, the COR returned by the damping, and oblique
# impacts at constant speed, at constant normal speed with a varying tangential speed or spin, and of two spheres
# spinning. The codes compare with theory or finite elements by eye, on digitised curves. Here each test is
# solved with the exact contact of this project: Hertz's normal force (elastic, or Hunt–Crossley damping set so
# that every row's normal COR is the test's), and the exact elastic microslip tangential contact
# (Cattaneo–Mindlin for any loading history, checked in `tests/test_microslip.py` against the Cattaneo–Mindlin
# curve and Maw's gross-slip line). Two spheres are solved exactly as one sphere on the flat (m*, R*, α*).
#
# Beside the exact contact: the simplified rules DEM codes run (`mindlin` on force increments, `mindlin-displacement`
# on the total displacement, `linear` springs with a linear spring-dashpot normal law, the `rigid` Coulomb contact).
# The inputs and the source of every number are in `src/sphereimpact/study/chung_ooi.yaml`; the reference files
# (`sphereimpact benchmark chung-ooi --out DIR`) are what a DEM code compares with (`sphereimpact benchmark compare`).
# Nothing here re-simulates: the notebook reads the tables the pipeline wrote (`results/chung_ooi/`).

# %%
import pandas as pd
import yaml
from IPython.display import Image, Markdown, display

from sphereimpact.study.chung_ooi import read_table
from sphereimpact.study.chung_ooi_definition import load_tests

config = yaml.safe_load(open("results/config.yaml"))  # the configuration the pipeline ran
numbers = config["chung_ooi"]["tests"]
_, tests = load_tests()
checks = pd.read_csv("results/chung_ooi/checks.csv")
deviations = pd.read_csv("results/chung_ooi/deviations.csv")
display(Markdown(f"Tests solved in this run: {', '.join(map(str, numbers))}."))

# %% [markdown]
# ## Each reference against its independent check
#
# The elastic rows against Hertz's closed forms (maximum overlap, peak force, contact time of two bodies with m*,
# R* and E*); every row's COR against the one the test asks for; the rows of tests 5 and 6 that slide throughout
# against the gross-slip line v_t' = v_t − μ(1 + e)v_n. The differences are the solver's tolerances.

# %%
display(checks.style.format({"max_rel": "{:.2e}"}).hide(axis="index"))

# %% [markdown]
# ## What the exact elastic solution neglects
#
# Between two different elastic materials the normal pressure also pulls the surfaces tangentially: the coupling
# measured by Dundurs' β (Johnson, *Contact Mechanics*, 1985, §5.7). Like spheres have β = 0, so tests 1, 7 and 8
# are exact in this respect; against a rigid plane β = (1 − 2ν)/(2(1 − ν)), which the DEM contact laws, like the
# solution here, leave out (Chung & Ooi's finite elements include it).

# %%
rows = []
for number in numbers:
    table = read_table(f"results/chung_ooi/test{number}.csv").drop_duplicates("case")
    for _, row in table.iterrows():
        rows.append({"test": number, "case": row["case"], "E* [Pa]": row["modulus"], "kappa": row["kappa"],
                     "Dundurs' beta": row["dundurs_beta"]})
display(pd.DataFrame(rows).style.format({"E* [Pa]": "{:.4g}", "kappa": "{:.4f}", "Dundurs' beta": "{:.3f}"})
        .hide(axis="index"))

# %% [markdown]
# ## The DEM rules against the exact contact
#
# For each oblique test and rule, the largest deviation over the test's rows, absolute and relative to the largest
# magnitude of the exact column.

# %%
if len(deviations):
    display(deviations.style.format({"max_abs": "{:.3g}", "max_rel": "{:.3g}"}).hide(axis="index"))

# %% [markdown]
# ## One figure per test
#
# Tests 1–3: each computed value against its reference (on the diagonal when they agree). Tests 4–8: the ball's
# tangential velocity, spin and contact-point rebound angle against the varied input, the exact contact solid and
# each DEM rule in its own line style; test 4 with the Kharaz et al. (2001) measurements (alumina on glass: the
# test's alumina on a rigid plane is the nearest case).

# %%
for number in numbers:
    display(Markdown(f"**Test {number}**: {tests[number]['title']}"))
    display(Image(f"paper_figures/chung_ooi_test{number}.png"))

# %% [markdown]
# ## What a DEM code's tangential rule costs
#
# Each rule's largest departure from the exact elastic microslip contact on the oblique tests on a plane and on the
# Kharaz ball over the validation's incidences (`+dashpot`: Kratos' tangential dashpot set from the scenes' normal
# COR), relative to the exact quantity's largest magnitude.

# %%
departure = pd.read_csv("results/chung_ooi/departure.csv")
display(departure.pivot_table(index="rule", columns=["scenes", "quantity"], values="max_rel", sort=False)
        .style.format("{:.2g}"))
display(Image("paper_figures/dem_departure.png"))
