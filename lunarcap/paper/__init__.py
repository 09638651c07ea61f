"""Song et al. (2011): every number the paper prints (``printed``), its consistency (``audit``)."""
