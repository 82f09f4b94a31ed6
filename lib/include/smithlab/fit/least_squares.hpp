// placeholder (issue 12)
#pragma once
