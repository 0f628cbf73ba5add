"""A small parameter sweep into a pandas DataFrame: how far the paper's interior pressure
slope is from the FE's as the block thickens, at F/N = 0.82.

    python3 python/examples/sweep_dataframe.py
"""

import tribofe

df = tribofe.sweep(thickness="0.001:0.008:4g", height=[0.02, 0.04, 0.08]).to_pandas()
view = df[df["FN"] == 0.82][["thickness_m", "height_m", "slope_ratio", "slope_ratio_corrected"]]
print(view.to_string(index=False))
